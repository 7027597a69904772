// provenance.cpp - the JSON provenance record of a fitted model (provenance.hpp).
#include "provenance.hpp"

#include <nettle/sha2.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>

#include "gmmrrt/limits.h"
#include "nlohmann/json.hpp"

#ifndef GMMRRT_VERSION_STRING
#error "GMMRRT_VERSION_STRING (the project version) must be defined by the build"
#endif

namespace gmmrrt {
namespace learn {
namespace cli {

namespace {

std::string Hex(const uint8_t* d, size_t n) {
  static const char kDigits[] = "0123456789abcdef";
  std::string s;
  for (size_t i = 0; i < n; ++i) {
    s += kDigits[d[i] >> 4];
    s += kDigits[d[i] & 15];
  }
  return s;
}

// Hashes the file into both the file's own context and the running one over all data files.
Status HashInto(const std::string& path, sha256_ctx* all, std::string* hex, uint64_t* bytes) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr)
    return Status::Error(StatusCode::kIoError, path + ": cannot read for the provenance hash: " + std::strerror(errno));
  sha256_ctx one;
  sha256_init(&one);
  uint64_t total = 0;
  std::vector<uint8_t> buf(1 << 16);
  size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0) {
    sha256_update(&one, n, buf.data());
    if (all != nullptr) sha256_update(all, n, buf.data());
    total += n;
  }
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) return Status::Error(StatusCode::kIoError, path + ": read error while hashing it for the provenance");
  uint8_t digest[SHA256_DIGEST_SIZE];
  sha256_digest(&one, sizeof digest, digest);
  *hex = Hex(digest, sizeof digest);
  *bytes = total;
  return Status::Ok();
}

std::string UtcNow() {
  std::time_t t = std::time(nullptr);
  const char* epoch = std::getenv("SOURCE_DATE_EPOCH");
  if (epoch != nullptr && *epoch != '\0') {
    char* end = nullptr;
    const long long v = std::strtoll(epoch, &end, 10);
    if (*end == '\0' && v >= 0) t = static_cast<std::time_t>(v);
  }
  std::tm tm{};
  gmtime_r(&t, &tm);
  char out[32];
  std::strftime(out, sizeof out, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return out;
}

std::string Dump(const nlohmann::ordered_json& j) {
  // Paths and arguments need not be UTF-8; the trailer must be: replace what is not.
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace

Status Sha256File(const std::string& path, std::string* hex, uint64_t* bytes) {
  return HashInto(path, nullptr, hex, bytes);
}

Status ProvenanceJson(const FitRecord& r, std::string* json) {
  sha256_ctx all;
  sha256_init(&all);
  uint64_t all_bytes = 0;
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  for (const std::string& p : r.data_files) {
    std::string hex;
    uint64_t n = 0;
    Status s = HashInto(p, &all, &hex, &n);
    if (!s.ok()) return s;
    all_bytes += n;
    files.push_back({{"path", p}, {"bytes", n}, {"sha256", hex}});
  }
  nlohmann::ordered_json indexes = nlohmann::ordered_json::array();
  for (const std::string& p : r.index_files) {
    std::string hex;
    uint64_t n = 0;
    Status s = HashInto(p, nullptr, &hex, &n);
    if (!s.ok()) return s;
    indexes.push_back({{"path", p}, {"bytes", n}, {"sha256", hex}});
  }
  uint8_t digest[SHA256_DIGEST_SIZE];
  sha256_digest(&all, sizeof digest, digest);

  nlohmann::ordered_json j;
  j["learner"] = std::string("gmmrrt-learn ") + GMMRRT_VERSION_STRING;
  j["created_utc"] = UtcNow();
  j["command_line"] = r.command_line;
  j["data_sha256"] = Hex(digest, sizeof digest);
  j["data_bytes"] = all_bytes;
  j["data_files"] = files;
  if (!indexes.empty()) j["index_files"] = indexes;
  j["points"] = r.points;
  j["dim"] = r.dim;
  j["seed"] = r.seed;
  j["k_auto"] = r.k_auto;
  j["k"] = r.k;
  j["bic"] = r.bic;
  j["mean_log_likelihood"] = r.mean_log_likelihood;
  j["iterations"] = r.iterations;
  j["converged"] = r.converged;
  j["delta"] = r.delta;

  std::string out = Dump(j);
  const size_t cap = GMMRRT_MAX_PROVENANCE_BYTES;
  if (out.size() > cap) {  // many inputs: the combined hash still names the data
    const size_t n_files = r.data_files.size() + r.index_files.size();
    j.erase("data_files");
    j.erase("index_files");
    j["data_files_omitted"] = n_files;
    out = Dump(j);
  }
  if (out.size() > cap) {  // then keep the command line's head, argument by argument
    std::vector<std::string> head = r.command_line;
    while (!head.empty() && out.size() > cap) {
      head.pop_back();
      j["command_line"] = head;
      j["command_line_truncated"] = true;
      out = Dump(j);
    }
  }
  if (out.size() > cap)
    return Status::Error(StatusCode::kInvalidArgument, "the provenance record does not fit in " +
                                                           std::to_string(cap) + " bytes");
  *json = out;
  return Status::Ok();
}

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt
