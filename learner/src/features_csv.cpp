// features_csv.cpp - the --features-csv reader (see features_csv.hpp).
#include "gmmrrt_learner/features_csv.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <vector>

#include "gmmrrt/limits.h"

namespace gmmrrt {
namespace learn {

namespace {

std::string Trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

// Splits on commas; false (with the bad field in *why) when a field is not a whole number.
bool ParseRow(const std::string& line, std::vector<double>* row, std::string* why) {
  row->clear();
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    const std::string field = Trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (field.empty()) {
      *why = "empty field";
      return false;
    }
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(field.c_str(), &end);
    if (end == field.c_str() || *end != '\0') {
      *why = "'" + field + "' is not a number";
      return false;
    }
    if (!std::isfinite(v) || errno == ERANGE) {
      *why = "'" + field + "' is not a finite number";
      return false;
    }
    row->push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return true;
}

// A header names columns: no field of it starts like a number (so "nan" or "1e" are not headers
// but bad rows).
bool IsHeader(const std::string& line) {
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    const std::string field = Trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    char* end = nullptr;
    std::strtod(field.c_str(), &end);
    if (field.empty() || end != field.c_str()) return false;
    if (comma == std::string::npos) return true;
    start = comma + 1;
  }
}

}  // namespace

Status ReadFeaturesCsv(const std::string& path, Eigen::MatrixXd* points) {
  std::ifstream in(path);
  if (!in) return Status::Error(StatusCode::kIoError, path + ": cannot open: " + std::strerror(errno));
  std::vector<double> values, row;
  std::string line, why;
  int dim = 0;
  long line_no = 0;
  bool first_content = true;
  while (std::getline(in, line)) {
    ++line_no;
    // A UTF-8 byte order mark (spreadsheet exports write one) is not part of the first field.
    if (line_no == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);
    const std::string t = Trim(line);
    if (t.empty() || t[0] == '#') continue;
    if (!ParseRow(t, &row, &why)) {
      if (first_content && IsHeader(t)) {
        first_content = false;
        continue;
      }
      return Status::Error(StatusCode::kBadInput, path + ":" + std::to_string(line_no) + ": " + why);
    }
    first_content = false;
    if (dim == 0) {
      dim = static_cast<int>(row.size());
      if (dim > GMMRRT_MAX_DIM)
        return Status::Error(StatusCode::kBadInput, path + ":" + std::to_string(line_no) + ": " +
                                                        std::to_string(dim) + " columns, at most " +
                                                        std::to_string(GMMRRT_MAX_DIM) + " allowed");
    } else if (static_cast<int>(row.size()) != dim) {
      return Status::Error(StatusCode::kBadInput, path + ":" + std::to_string(line_no) + ": " +
                                                      std::to_string(row.size()) + " columns, expected " +
                                                      std::to_string(dim));
    }
    values.insert(values.end(), row.begin(), row.end());
  }
  if (in.bad()) return Status::Error(StatusCode::kIoError, path + ": read error");
  if (dim == 0) return Status::Error(StatusCode::kNotEnoughData, path + ": no data rows");
  *points = Eigen::Map<const Eigen::MatrixXd>(values.data(), dim, static_cast<Eigen::Index>(values.size() / dim));
  return Status::Ok();
}

Status ParseAngleDims(const std::string& text, int dim, uint32_t* mask) {
  *mask = 0;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = text.find(',', start);
    const std::string field = Trim(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    char* end = nullptr;
    const long v = std::strtol(field.c_str(), &end, 10);
    if (field.empty() || *end != '\0' || v < 1 || v > dim)
      return Status::Error(StatusCode::kInvalidArgument,
                           "--angle-dims: '" + field + "' is not a dimension number in 1.." + std::to_string(dim));
    *mask |= 1u << (v - 1);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return Status::Ok();
}

}  // namespace learn
}  // namespace gmmrrt
