#pragma once
// A file the user names (a scenario, a texture, a vessel map, a mesh, a trace, a shard), as the
// messages about it name it, and the check every reader makes before opening one.
#include <cstdint>
#include <fstream>
#include <string>

#include "core/runtime/input_error.h"

namespace bleedsim {

struct InputFile {
  std::string path;
  std::string what;  // "scenario file", "texture", "vessel map", "shard file": what it is to bleedsim
  std::string key = {};    // the scenario key that names it; empty for a file given on the command line
  SourcePlace where = {};  // where that key was written
};

// "x.toml:12:7: vessels.map: cannot read vessel map 'v.png': <why>" for a file a key names;
// "v.toml: cannot read scenario file: <why>", placed at the file itself, for one without a key.
InputError unreadable(const InputFile& file, const std::string& why);

// Throws InputError unless `file.path` is a regular file (after links): for an empty path ("is
// empty", at the key), a missing one, and anything else, naming what it is ("a named pipe", "a
// directory", "a character device"). Looks with stat() and never opens the file: opening a named
// pipe waits for a writer, forever.
void require_regular_file(const InputFile& file);

// The file opened for reading, binary: the same refusals as require_regular_file, and unreadable()
// for a file that cannot be opened (no permission).
std::ifstream open_input(const InputFile& file);

// FNV-1a 64 of the file's bytes, read in pieces; the same refusals as require_regular_file, and
// unreadable() for a file that cannot be read.
std::uint64_t hash_of_file(const InputFile& file);

}  // namespace bleedsim
