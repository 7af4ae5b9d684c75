#pragma once
// Files in and out, with the errors a user can act on. Inputs: a missing path, a folder where a file is
// expected and an unreadable file each get their own message naming the path. Outputs: written under a
// temporary name beside the target and renamed only when complete, so a run that stops half-way never leaves
// a file that looks like a finished result.
#include <fstream>
#include <string>

namespace ccdlab {

/// The whole content of a file. Throws Error "PATH: cannot open file (…)" naming why: no such file, a
/// directory, permission denied, read error.
std::string read_file(const std::string& path);

/// Throws Error naming `path` unless it is an existing regular file that can be opened for reading.
void check_input_file(const std::string& path);

/// An output file written to "PATH.partial" and renamed to PATH by commit(). Destroyed uncommitted (an error,
/// an interrupted run) it removes the partial file. `what` names the option or key the path came from, for
/// errors ("--contacts: cannot write 'x.csv': …").
class OutputFile {
 public:
  OutputFile() = default;
  OutputFile(std::string path, std::string what);
  OutputFile(OutputFile&& other) noexcept;
  OutputFile& operator=(OutputFile&& other) noexcept;
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();

  [[nodiscard]] bool is_open() const { return out_.is_open(); }
  template <class T>
  OutputFile& operator<<(const T& value) {
    out_ << value;
    return *this;
  }
  /// Flushes, checks that every write succeeded, renames to the final path. Throws Error otherwise.
  void commit();
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  void discard() noexcept;
  std::string path_, partial_, what_;
  std::ofstream out_;
};

/// Creates the folder `dir` (and its parents) for results; Error naming `what` (the option or key) otherwise.
void create_output_dir(const std::string& dir, const std::string& what);

/// Removes `path` if it exists (a stale result of an earlier run that this run will replace); Error if it
/// cannot be removed.
void remove_stale_output(const std::string& path, const std::string& what);

}  // namespace ccdlab
