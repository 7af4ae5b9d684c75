#include "framework/util/files.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "framework/util/error.hpp"

namespace ccdlab {
namespace fs = std::filesystem;

void check_input_file(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (path.empty()) fail("cannot open file: empty path");
  if (!fs::exists(st)) fail("{}: cannot open file (no such file)", path);
  if (fs::is_directory(st)) fail("{}: cannot open file (it is a directory, expected a file)", path);
  if (!fs::is_regular_file(st) && !fs::is_fifo(st) && !fs::is_character_file(st))
    fail("{}: cannot open file (not a regular file)", path);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open file ({})", path, std::strerror(errno));
}

std::string read_file(const std::string& path) {
  check_input_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open file ({})", path, std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) fail("{}: read error", path);
  return ss.str();
}

OutputFile::OutputFile(std::string path, std::string what)
    : path_(std::move(path)), partial_(path_ + ".partial"), what_(std::move(what)) {
  std::error_code ec;
  if (fs::is_directory(path_, ec)) fail("{}: cannot write '{}' (it is a directory)", what_, path_);
  out_.open(partial_, std::ios::binary | std::ios::trunc);
  if (!out_) fail("{}: cannot write '{}' ({})", what_, path_, std::strerror(errno));
}

OutputFile::OutputFile(OutputFile&& other) noexcept
    : path_(std::move(other.path_)), partial_(std::move(other.partial_)), what_(std::move(other.what_)),
      out_(std::move(other.out_)) {
  other.partial_.clear();
}

OutputFile& OutputFile::operator=(OutputFile&& other) noexcept {
  if (this != &other) {
    discard();
    path_ = std::move(other.path_);
    partial_ = std::move(other.partial_);
    what_ = std::move(other.what_);
    out_ = std::move(other.out_);
    other.partial_.clear();
  }
  return *this;
}

OutputFile::~OutputFile() { discard(); }

void OutputFile::discard() noexcept {
  if (partial_.empty()) return;
  if (out_.is_open()) out_.close();
  std::error_code ec;
  fs::remove(partial_, ec);
  partial_.clear();
}

void OutputFile::commit() {
  if (partial_.empty()) return;
  out_.flush();
  const bool ok = bool(out_);
  out_.close();
  if (!ok || out_.fail()) fail("{}: write failed for '{}' (disk full?)", what_, path_);
  std::error_code ec;
  fs::rename(partial_, path_, ec);
  if (ec) fail("{}: cannot rename '{}' to '{}': {}", what_, partial_, path_, ec.message());
  partial_.clear();
}

void create_output_dir(const std::string& dir, const std::string& what) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) fail("{}: cannot create '{}': a file of that name exists", what, dir);
  fs::create_directories(dir, ec);
  if (ec) fail("{}: cannot create '{}': {}", what, dir, ec.message());
}

void remove_stale_output(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (!fs::exists(path, ec) || fs::is_directory(path, ec)) return;
  fs::remove(path, ec);
  if (ec) fail("{}: cannot replace '{}': {}", what, path, ec.message());
}

}  // namespace ccdlab
