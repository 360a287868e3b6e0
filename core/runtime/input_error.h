#pragma once
#include <stdexcept>
#include <string>

namespace bleedsim {

// Where in a user's file a value came from; line 0 means "the file as a whole".
struct SourcePlace {
  std::string file;
  int line = 0;
  int column = 0;
};

// Bad input from the user (a scenario, a texture, an output path): the CLI prints it and exits 2.
// what() reads "file:line:column: key: message", with the parts that are known.
class InputError : public std::runtime_error {
 public:
  InputError(const SourcePlace& where, const std::string& key, const std::string& message);
  const SourcePlace& where() const { return where_; }
  const std::string& key() const { return key_; }

 private:
  SourcePlace where_;
  std::string key_;
};

}  // namespace bleedsim
