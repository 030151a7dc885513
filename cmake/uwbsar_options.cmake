# uwbsar_configure_target(<target>): the project's warning, optimisation and
# sanitizer flags, applied to every target so that all of them agree.
include(CheckCXXCompilerFlag)
check_cxx_compiler_flag(-march=native UWBSAR_HAS_MARCH_NATIVE)

function(uwbsar_configure_target target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wconversion -Wno-sign-conversion)
  # No errno from sqrt etc.: lets the back-projection inner loops vectorise.
  target_compile_options(${target} PRIVATE -fno-math-errno)
  if(UWBSAR_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(UWBSAR_NATIVE AND UWBSAR_HAS_MARCH_NATIVE)
    target_compile_options(${target} PRIVATE -march=native)
  endif()
  if(UWBSAR_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=undefined)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()
