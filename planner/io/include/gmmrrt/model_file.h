/*
 * model_file.h - reading and atomically writing model files (format: model.h and
 * docs/model-format.md). Kept out of the planner core, which does no I/O: the learner
 * CLI, the planner CLI and the daemon link gmmrrt_io for these two calls.
 */
#ifndef GMMRRT_MODEL_FILE_H
#define GMMRRT_MODEL_FILE_H

#include <stddef.h>

#include "gmmrrt/model.h"
#include "gmmrrt/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Reads the model file at `path` into *model. Reads at most
 * gmmrrt_model_max_encoded_size() + 1 bytes, so an oversized file is rejected as
 * GMMRRT_ERR_MODEL_TOO_LARGE without reading it all. The file is decoded into a scratch
 * model and *model is overwritten only when the result is GMMRRT_OK: on any failure the
 * caller's model is untouched (the cFE table pattern).
 * Returns GMMRRT_OK; GMMRRT_ERR_INVALID_ARGUMENT (NULL path or model);
 * GMMRRT_ERR_IO when the file cannot be opened or read (err names the path and the
 * system's reason); or the GMMRRT_ERR_MODEL_* status of gmmrrt_model_decode().
 * err[errcap] (may be NULL) receives a message starting with the path. */
gmmrrt_status_t gmmrrt_model_load_file(const char *path, gmmrrt_model_t *model, char *err, size_t errcap);

/* Writes *model to `path` atomically: the encoding goes to a temporary file in the same
 * directory, which is written, fsync'ed and renamed over `path` (the directory is then
 * fsync'ed). On any failure the temporary file is removed and `path` is left as it was:
 * never a partial model. The new file gets mode 0644. An existing `path` that is not a
 * regular file (device node, FIFO, directory, or a symbolic link to one) is refused with
 * GMMRRT_ERR_IO and left alone.
 * Returns GMMRRT_OK; GMMRRT_ERR_INVALID_ARGUMENT (NULL path or model); the
 * GMMRRT_ERR_MODEL_* status when the model does not validate (nothing is written); or
 * GMMRRT_ERR_IO with the path and the system's reason. */
gmmrrt_status_t gmmrrt_model_save_file(const char *path, const gmmrrt_model_t *model, char *err,
                                       size_t errcap);

/* As gmmrrt_model_load_file, and the file's provenance text (gmmrrt_model_provenance:
 * NUL-terminated, *text_len = 0 when the file has none) into text[text_cap] when text is not
 * NULL; a text_cap below the text's length + 1 is GMMRRT_ERR_BUFFER_TOO_SMALL
 * (GMMRRT_MAX_PROVENANCE_BYTES + 1 always suffices). Neither *model nor text is trusted
 * unless the call returns GMMRRT_OK; *model is untouched on failure. */
gmmrrt_status_t gmmrrt_model_load_file_provenance(const char *path, gmmrrt_model_t *model, char *text,
                                                  size_t text_cap, size_t *text_len, char *err, size_t errcap);

/* As gmmrrt_model_save_file, with a provenance trailer holding text[0..text_len)
 * (gmmrrt_model_encode_provenance; text NULL writes no trailer, as gmmrrt_model_save_file). */
gmmrrt_status_t gmmrrt_model_save_file_provenance(const char *path, const gmmrrt_model_t *model, const char *text,
                                                  size_t text_len, char *err, size_t errcap);

/* As gmmrrt_model_load_file_provenance (text may be NULL), and the file's background model
 * (gmmrrt_model_background) into *background when background is not NULL: *has_background = 1
 * and *background overwritten when the file has one, *has_background = 0 and *background
 * untouched when it has none. A bad background fails the whole load (its status; nothing of
 * the caller's is touched). */
gmmrrt_status_t gmmrrt_model_load_file_background(const char *path, gmmrrt_model_t *model, gmmrrt_model_t *background,
                                                  int *has_background, char *text, size_t text_cap, size_t *text_len,
                                                  char *err, size_t errcap);

/* As gmmrrt_model_save_file_provenance, with a background section holding *background when it
 * is not NULL (gmmrrt_model_encode_file: it must match the model). */
gmmrrt_status_t gmmrrt_model_save_file_background(const char *path, const gmmrrt_model_t *model,
                                                  const gmmrrt_model_t *background, const char *text, size_t text_len,
                                                  char *err, size_t errcap);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_MODEL_FILE_H */
