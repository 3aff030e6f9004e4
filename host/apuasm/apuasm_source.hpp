// Source files: reading them (refusing what is not a file) and naming the file
// an .include means. Internal to apuasm_lib.
#pragma once

#include <stdexcept>
#include <string>

namespace mc1::apuasm::detail {

// Why a source file could not be read: "is a directory", "larger than 16
// MiB" (kMaxSourceBytes), or the system's reason ("No such file or directory"). The caller names the file and place.
class SourceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The bytes of the file `path`, at most kMaxSourceBytes of them (it reads
// one more to tell); throws SourceError.
std::string read_source(const std::string& path);

// The file `.include "name"` in `from_file` reads: `name` itself when
// absolute, else relative to the directory of `from_file`.
std::string include_path(const std::string& from_file, const std::string& name);

}  // namespace mc1::apuasm::detail
