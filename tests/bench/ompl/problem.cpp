/*
 * problem.cpp - loading the task model for the benchmark problem (problem.hpp): the file
 * is read whole and validated by the one decoder of the format (model.h).
 */
#include "problem.hpp"

#include <fstream>
#include <iterator>
#include <vector>

#include "gmmrrt/status.h"

namespace gmmrrt_bench {

bool load_model_file(const std::string &path, gmmrrt_model_t *out, std::string *err)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        *err = "cannot open model file '" + path + "'";
        return false;
    }
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() > gmmrrt_model_max_file_size()) {
        *err = "model file '" + path + "' is larger than any valid model";
        return false;
    }
    char msg[256] = "";
    const gmmrrt_status_t st = gmmrrt_model_decode(bytes.data(), bytes.size(), out, msg, sizeof msg);
    if (st != GMMRRT_OK) {
        *err = "model file '" + path + "': " + gmmrrt_status_str(st) + ": " + msg;
        return false;
    }
    if (out->kind != GMMRRT_MODEL_KIND_FEATURES) {
        *err = "model file '" + path + "' is not a (d, theta) FEATURES model";
        return false;
    }
    return true;
}

} // namespace gmmrrt_bench
