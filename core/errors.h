// Error types shared by every layer. Bad input from the outside world (files,
// serial bytes, user flags) throws an InputError whose what() is one complete
// line naming the file/offset/field; the CLI maps it to exit code 3.
#pragma once

#include <stdexcept>
#include <string>

namespace uwbsar {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace uwbsar
