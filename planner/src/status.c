/* status.c - gmmrrt_status_str (status.h). */
#include "gmmrrt/status.h"

const char *gmmrrt_status_str(gmmrrt_status_t status)
{
    switch (status) {
    case GMMRRT_OK: return "ok";
    case GMMRRT_ERR_INVALID_ARGUMENT: return "invalid argument";
    case GMMRRT_ERR_BUFFER_TOO_SMALL: return "buffer too small";
    case GMMRRT_ERR_MODEL_TRUNCATED: return "model file truncated";
    case GMMRRT_ERR_MODEL_BAD_MAGIC: return "not a gmmrrt model file (bad magic)";
    case GMMRRT_ERR_MODEL_BAD_VERSION: return "unsupported model format version";
    case GMMRRT_ERR_MODEL_BAD_BYTE_ORDER: return "model byte order is not little-endian";
    case GMMRRT_ERR_MODEL_BAD_SIZE: return "model dimension, component count or length out of range";
    case GMMRRT_ERR_MODEL_BAD_CHECKSUM: return "model checksum mismatch";
    case GMMRRT_ERR_MODEL_NOT_FINITE: return "model holds a NaN or Inf";
    case GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE: return "model covariance is not positive definite";
    case GMMRRT_ERR_MODEL_BAD_WEIGHTS: return "model weights are not a distribution";
    case GMMRRT_ERR_MODEL_BAD_FIELD: return "model header field has an unknown value";
    case GMMRRT_ERR_MODEL_TOO_LARGE: return "model file larger than any valid model";
    case GMMRRT_ERR_IO: return "i/o error";
    case GMMRRT_ERR_START_IN_COLLISION: return "start in collision";
    case GMMRRT_ERR_GOAL_IN_COLLISION: return "goal in collision";
    case GMMRRT_ERR_START_OUT_OF_BOUNDS: return "start outside the planning bounds";
    case GMMRRT_ERR_GOAL_OUT_OF_BOUNDS: return "goal outside the planning bounds";
    case GMMRRT_ERR_MODEL_MISMATCH: return "model kind or dimension does not fit the planner";
    case GMMRRT_ERR_FROZEN: return "frozen: start in collision and no motion increases clearance";
    case GMMRRT_ESCAPE: return "escaping: start in collision, the path leaves it first";
    case GMMRRT_NO_PATH_YET: return "no path yet";
    case GMMRRT_NO_PATH_ON_SIDE: return "no path on the preferred side";
    case GMMRRT_TIGHT_TURNS: return "path turns tighter than the minimum turning radius somewhere";
    case GMMRRT_POOL_FULL: return "node pool full";
    case GMMRRT_TIMEOUT: return "timeout";
    }
    return "unknown status";
}
