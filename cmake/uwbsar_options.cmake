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
  if(UWBSAR_SANITIZE)
    # GCC 12 reports false maybe-uninitialized warnings inside Eigen/intrinsics under ASan.
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=undefined
                                             -Wno-maybe-uninitialized)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# uwbsar_native_sources(<files>...): the hot loops that gain from the build machine's
# vector units (back-projection gathers). Only these files get -march=native: the rest
# of the project shares Eigen types with Debian's Ceres and PCL, which are built for the
# x86-64 baseline, and Eigen's alignment (16 vs 32/64 bytes) must agree across them.
function(uwbsar_native_sources)
  if(UWBSAR_NATIVE AND UWBSAR_HAS_MARCH_NATIVE)
    set_source_files_properties(${ARGN} PROPERTIES COMPILE_OPTIONS -march=native)
  endif()
endfunction()
