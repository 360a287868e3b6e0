#include "core/scaleout/shard_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "core/runtime/hash.h"
#include "core/runtime/input_error.h"
#include "core/runtime/input_file.h"
#include "core/scaleout/byte_codec.h"

namespace bleedsim {
namespace {

constexpr char kMagic[8] = {'B', 'L', 'E', 'E', 'D', 'S', 'H', 'D'};
constexpr std::uint32_t kVersion = 1;
// The magic, the version and the file's length come first; the checksum last.
constexpr std::size_t kPrologueBytes = sizeof kMagic + 4 + 8;
constexpr std::size_t kChecksumBytes = 8;
constexpr int kMostShards = 1000000;

InputError file_error(const std::string& path, const std::string& message) {
  return InputError(SourcePlace{path, 0, 0}, "", message);
}

// Appends to a file descriptor, each write checked, keeping the FNV-1a 64 of what went in.
class ChecksummedFile {
 public:
  ChecksummedFile(const std::string& path, const std::string& shown) : shown_(shown) {
    fd_ = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd_ < 0) fail(errno);
  }
  ~ChecksummedFile() {
    if (fd_ >= 0) close(fd_);
  }
  void write_bytes(const void* data, std::size_t size) {
    hash_ = fnv1a64(data, size, hash_);
    const auto* p = static_cast<const std::uint8_t*>(data);
    for (std::size_t done = 0; done < size;) {
      const ssize_t n = write(fd_, p + done, size - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) fail(errno);
      done += std::size_t(n);
    }
  }
  void write_bytes(const std::vector<std::uint8_t>& bytes) { write_bytes(bytes.data(), bytes.size()); }
  // The checksum, then the file flushed to disk and closed.
  void finish() {
    ByteWriter checksum;
    checksum.u64(hash_);
    write_bytes(checksum.data());
    if (fsync(fd_) != 0) fail(errno);
    const int fd = fd_;
    fd_ = -1;
    if (close(fd) != 0) fail(errno);
  }

 private:
  [[noreturn]] void fail(int reason) const {
    throw std::runtime_error("cannot write shard file '" + shown_ + "': " + std::strerror(reason));
  }
  int fd_ = -1;
  std::string shown_;
  std::uint64_t hash_ = fnv1a64(nullptr, 0);
};

std::vector<std::uint8_t> read_whole_file(const std::string& path) {
  const InputFile file{path, "shard file"};
  require_regular_file(file);
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw unreadable(file, std::strerror(errno));
  struct stat info {};
  std::vector<std::uint8_t> bytes;
  int reason = 0;
  if (fstat(fd, &info) != 0) {
    reason = errno;
  } else {
    bytes.resize(std::size_t(info.st_size));
    for (std::size_t done = 0; done < bytes.size() && !reason;) {
      const ssize_t n = read(fd, bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) reason = errno;
      if (n == 0) bytes.resize(done);  // shrank while read: the checks below say so
      done += n > 0 ? std::size_t(n) : 0;
    }
  }
  close(fd);
  if (reason) throw unreadable(file, std::strerror(reason));
  return bytes;
}

// What precedes a job's record in the file: its index, its origin and the record's length.
ByteWriter job_label(const JobResult& result) {
  ByteWriter label;
  label.u64(result.job);
  write_origin(label, result.origin);
  label.u64(result.record.size());
  return label;
}

std::string shard_text(ShardId shard) { return std::to_string(shard.index) + "/" + std::to_string(shard.count); }

}  // namespace

ShardId parse_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  const std::string i = text.substr(0, slash), k = slash == std::string::npos ? "" : text.substr(slash + 1);
  const auto whole = [](const std::string& s) {
    return !s.empty() && s.size() <= 7 && s.find_first_not_of("0123456789") == std::string::npos;
  };
  if (!whole(i) || !whole(k))
    throw InputError({}, "--shard", "write it as i/K, shard i of K counted from 0 (e.g. 0/4 to 3/4), not '" + text + "'");
  const ShardId shard{std::stoi(i), std::stoi(k)};
  if (shard.count < 1 || shard.count > kMostShards)
    throw InputError({}, "--shard", "K must be from 1 to " + std::to_string(kMostShards) + " (got '" + text + "')");
  if (shard.index >= shard.count)
    throw InputError({}, "--shard", "i counts from 0, so it must be below K: " + text + " has no shard " + i +
                                        " (the last is " + std::to_string(shard.count - 1) + "/" + k + ")");
  return shard;
}

std::string shard_file_name(ShardId shard) {
  std::string index = std::to_string(shard.index);
  const std::string count = std::to_string(shard.count);
  index.insert(0, count.size() > index.size() ? count.size() - index.size() : 0, '0');
  return "shard-" + index + "-of-" + count + ".bleedshard";
}

void write_shard(const std::string& path, const ShardContents& contents) {
  const ShardId shard = contents.shard;
  if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count)
    throw std::invalid_argument("write_shard: no shard " + shard_text(shard));
  for (std::size_t i = 0; i < contents.results.size(); ++i) {
    const std::size_t job = contents.results[i].job;
    if (job >= contents.job_count || (i > 0 && job <= contents.results[i - 1].job))
      throw std::invalid_argument("write_shard: the results must be ascending jobs below " +
                                  std::to_string(contents.job_count) + " (job " + std::to_string(job) + " at place " +
                                  std::to_string(i) + ")");
  }

  // Everything but the records is encoded first, so the prologue can say the file's length.
  ByteWriter head;
  head.text(contents.fingerprint);
  head.bytes(contents.study);
  head.u64(contents.job_count);
  head.u32(std::uint32_t(shard.index));
  head.u32(std::uint32_t(shard.count));
  head.u64(contents.results.size());
  std::vector<std::vector<std::uint8_t>> labels;  // each record's job, origin and length
  std::uint64_t length = kPrologueBytes + head.data().size() + kChecksumBytes;
  for (const JobResult& result : contents.results) {
    ByteWriter label = job_label(result);
    length += label.data().size() + result.record.size();
    labels.push_back(label.take());
  }
  ByteWriter prologue;
  prologue.raw(kMagic, sizeof kMagic);
  prologue.u32(kVersion);
  prologue.u64(length);

  // A name of its own beside the file: two writers of one shard cannot mix their bytes.
  const std::string partial = path + ".partial-" + std::to_string(getpid());
  try {
    ChecksummedFile file(partial, path);
    file.write_bytes(prologue.data());
    file.write_bytes(head.data());
    for (std::size_t i = 0; i < labels.size(); ++i) {
      file.write_bytes(labels[i]);
      file.write_bytes(contents.results[i].record);
    }
    file.finish();
    std::error_code error;
    std::filesystem::rename(partial, path, error);
    if (error) throw std::runtime_error("cannot write shard file '" + path + "': " + error.message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    throw;
  }
}

ShardContents read_shard(const std::string& path) { return decode_shard(read_whole_file(path), path); }

ShardContents decode_shard(const std::vector<std::uint8_t>& bytes, const std::string& path) {
  if (bytes.size() < sizeof kMagic || !std::equal(kMagic, kMagic + sizeof kMagic, bytes.begin()))
    throw file_error(path, "not a bleedsim shard file (it does not begin as one)");
  if (bytes.size() < kPrologueBytes + kChecksumBytes)
    throw file_error(path, "the shard file is cut off: " + std::to_string(bytes.size()) + " bytes, too few for a shard");
  ByteReader in(bytes.data(), bytes.size());
  ShardContents contents;
  try {
    char magic[sizeof kMagic];
    in.raw(magic, sizeof magic, "the magic");
    const std::uint32_t version = in.u32("the format version");
    if (version != kVersion)
      throw file_error(path, "a shard file of format version " + std::to_string(version) + "; this bleedsim reads version " +
                                 std::to_string(kVersion));
    const std::uint64_t length = in.u64("the file's length");
    if (bytes.size() < length)
      throw file_error(path, "the shard file is cut off: " + std::to_string(bytes.size()) + " of its " +
                                 std::to_string(length) + " bytes (copied while being written?)");
    if (bytes.size() > length)
      throw file_error(path, "the shard file is damaged: " + std::to_string(bytes.size() - length) +
                                 " bytes more than the " + std::to_string(length) + " it says it has");
    const std::size_t body = bytes.size() - kChecksumBytes;
    ByteReader tail(bytes.data() + body, kChecksumBytes);
    if (tail.u64("the checksum") != fnv1a64(bytes.data(), body))
      throw file_error(path, "the shard file is damaged: its checksum does not match its contents");

    contents.fingerprint = in.text("the fingerprint");
    contents.study = in.bytes("the study's description");
    contents.job_count = in.u64("the job count");
    contents.shard.index = int(in.u32("the shard's index"));
    contents.shard.count = int(in.u32("the shard count"));
    // The fewest bytes a job takes (an empty host and record): a damaged count cannot ask for more
    // jobs than the file holds.
    contents.results.resize(in.count("the result count", job_label(JobResult{}).data().size()));
    for (JobResult& result : contents.results) {
      result.job = in.u64("a job's index");
      const std::string job = "job " + std::to_string(result.job);
      result.origin = read_origin(in, job);
      result.record = in.bytes(job + "'s record");
    }
    if (in.offset() != body)
      throw file_error(path, "the shard file is damaged: " + std::to_string(body - in.offset()) +
                                 " bytes after its last record");
  } catch (const TruncatedBytes& e) {
    throw file_error(path, std::string("the shard file is damaged: ") + e.what());
  }
  const ShardId shard = contents.shard;
  if (shard.count < 1 || shard.count > kMostShards || shard.index < 0 || shard.index >= shard.count)
    throw file_error(path, "the shard file is damaged: it says it is shard " + shard_text(shard));
  for (std::size_t i = 0; i < contents.results.size(); ++i) {
    const std::size_t job = contents.results[i].job;
    if (job >= contents.job_count || (i > 0 && job <= contents.results[i - 1].job))
      throw file_error(path, "the shard file is damaged: job " + std::to_string(job) + " at place " + std::to_string(i) +
                                 " (the jobs must ascend, below the study's " + std::to_string(contents.job_count) + ")");
  }
  return contents;
}

MergedShards merge_shards(const std::vector<std::string>& paths) {
  if (paths.empty()) throw InputError({}, "", "no shard files to merge");
  MergedShards merged;
  std::size_t job_count = 0;
  std::vector<int> file_of_shard;                      // each shard's file, -1 until seen
  std::vector<std::pair<std::size_t, int>> job_files;  // (job, file) for every record
  std::vector<JobResult> results;
  for (std::size_t f = 0; f < paths.size(); ++f) {
    ShardContents shard = read_shard(paths[f]);
    if (f == 0) {
      merged.fingerprint = shard.fingerprint;
      merged.study = shard.study;
      merged.shard_count = std::size_t(shard.shard.count);
      job_count = shard.job_count;
      file_of_shard.assign(merged.shard_count, -1);
    }
    const std::string first = "'" + paths[0] + "'";
    if (shard.fingerprint != merged.fingerprint)
      throw file_error(paths[f], "a shard of another study than " + first + " (fingerprint " + shard.fingerprint +
                                     ", not " + merged.fingerprint +
                                     "): its scenario, a file it names or the study options differ");
    if (shard.study != merged.study)
      throw file_error(paths[f], "its study's description differs from " + first + "'s, under the same fingerprint");
    if (std::size_t(shard.shard.count) != merged.shard_count || shard.job_count != job_count)
      throw file_error(paths[f], "shard " + shard_text(shard.shard) + " of " + std::to_string(shard.job_count) +
                                     " jobs does not belong with " + first + ", one of " +
                                     std::to_string(merged.shard_count) + " shards of " + std::to_string(job_count) +
                                     " jobs");
    int& seen = file_of_shard[std::size_t(shard.shard.index)];
    if (seen >= 0)
      throw file_error(paths[f], "shard " + shard_text(shard.shard) + " again: '" + paths[std::size_t(seen)] +
                                     "' is that shard too");
    seen = int(f);
    for (JobResult& result : shard.results) {
      job_files.emplace_back(result.job, int(f));
      results.push_back(std::move(result));
    }
  }
  for (std::size_t s = 0; s < file_of_shard.size(); ++s)
    if (file_of_shard[s] < 0)
      throw InputError({}, "", "shard " + std::to_string(s) + "/" + std::to_string(merged.shard_count) +
                                   " is missing: none of the " + std::to_string(paths.size()) + " files given is that shard");

  // Every job once: sorted by job, a repeat sits beside its twin and a gap is a missing job.
  std::vector<std::size_t> order(results.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return job_files[a] < job_files[b]; });
  for (std::size_t i = 0; i < order.size(); ++i) {
    const auto [job, file] = job_files[order[i]];
    if (i > 0 && job == job_files[order[i - 1]].first)
      throw file_error(paths[std::size_t(file)], "job " + std::to_string(job) + " is also in '" +
                                                     paths[std::size_t(job_files[order[i - 1]].second)] + "'");
    if (job != i) throw InputError({}, "", "job " + std::to_string(i) + " is in none of the shard files");
  }
  if (order.size() < job_count)
    throw InputError({}, "", "job " + std::to_string(order.size()) + " is in none of the shard files");
  for (const std::size_t i : order) merged.results.push_back(std::move(results[i]));
  return merged;
}

}  // namespace bleedsim
