/*
 * model_file.c - model files on disk (model_file.h): bounded read + validating decode
 * into a scratch model (cFE table pattern, STYLE.md item 7), and atomic write
 * (temporary file in the same directory, write, fsync, rename, fsync the directory).
 * The byte format itself lives in planner/src/model.c (docs/model-format.md).
 */
#include "gmmrrt/model_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "error_text.h" /* planner/src, private include */

/* Reads up to cap bytes (fewer at end of file) into buf; -1 with errno on a read error. */
static ssize_t read_up_to(int fd, uint8_t *buf, size_t cap)
{
    size_t got = 0;
    while (got < cap) {
        const ssize_t n = read(fd, buf + got, cap - got);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            return -1;
        }
        if (n == 0)
            break;
        got += (size_t)n;
    }
    return (ssize_t)got;
}

gmmrrt_status_t gmmrrt_model_load_file(const char *path, gmmrrt_model_t *model, char *err, size_t errcap)
{
    return gmmrrt_model_load_file_provenance(path, model, NULL, 0, NULL, err, errcap);
}

gmmrrt_status_t gmmrrt_model_load_file_provenance(const char *path, gmmrrt_model_t *model, char *text,
                                                  size_t text_cap, size_t *text_len, char *err, size_t errcap)
{
    return gmmrrt_model_load_file_background(path, model, NULL, NULL, text, text_cap, text_len, err, errcap);
}

gmmrrt_status_t gmmrrt_model_load_file_background(const char *path, gmmrrt_model_t *model, gmmrrt_model_t *background,
                                                  int *has_background, char *text, size_t text_cap, size_t *text_len,
                                                  char *err, size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (path == NULL || model == NULL || (text != NULL && text_len == NULL) ||
        (background != NULL && has_background == NULL))
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap,
                                "model path or model is NULL, text without text_len, or background without "
                                "has_background");

    const size_t cap = gmmrrt_model_max_file_size() + 1; /* one more: detects oversized files */
    uint8_t *buf = malloc(cap);
    gmmrrt_model_t *scratch = malloc(sizeof *scratch);
    gmmrrt_model_t *bg_scratch = background != NULL ? malloc(sizeof *bg_scratch) : NULL;
    int has_bg = 0;
    gmmrrt_status_t st = GMMRRT_OK;
    if (buf == NULL || scratch == NULL || (background != NULL && bg_scratch == NULL)) {
        st = gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: out of memory reading the model", path);
        goto done;
    }
    /* O_NONBLOCK: opening a FIFO (or a device) must not block the caller (a daemon reloading
     * on SIGHUP, its watchdog waiting); anything but a regular file is refused below. */
    const int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) {
        st = gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: cannot open model file: %s", path,
                              strerror(errno));
        goto done;
    }
    struct stat sb;
    const int stat_ok = fstat(fd, &sb) == 0;
    if (!stat_ok || !S_ISREG(sb.st_mode)) {
        const int is_dir = stat_ok && S_ISDIR(sb.st_mode);
        close(fd);
        st = gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: %s, not a model file", path,
                              is_dir ? "is a directory" : "is not a regular file (a FIFO, device or socket)");
        goto done;
    }
    const ssize_t n = read_up_to(fd, buf, cap);
    const int read_errno = errno;
    close(fd);
    if (n < 0) {
        st = gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: cannot read model file: %s", path,
                              strerror(read_errno));
        goto done;
    }

    char why[256];
    st = gmmrrt_model_decode(buf, (size_t)n, scratch, why, sizeof why);
    if (st != GMMRRT_OK) {
        if ((size_t)n == cap)
            gmmrrt_set_error(st, err, errcap, "%s: more than %zu bytes: %s", path, cap - 1, why);
        else
            gmmrrt_set_error(st, err, errcap, "%s: %s", path, why);
        goto done;
    }
    if (text != NULL) {
        st = gmmrrt_model_provenance(buf, (size_t)n, text, text_cap, text_len, NULL, why, sizeof why);
        if (st != GMMRRT_OK) {
            gmmrrt_set_error(st, err, errcap, "%s: %s", path, why);
            goto done;
        }
    }
    if (background != NULL) {
        st = gmmrrt_model_background(buf, (size_t)n, bg_scratch, &has_bg, why, sizeof why);
        if (st != GMMRRT_OK) {
            gmmrrt_set_error(st, err, errcap, "%s: %s", path, why);
            goto done;
        }
    }
    memcpy(model, scratch, sizeof *model);
    if (background != NULL) {
        *has_background = has_bg;
        if (has_bg)
            memcpy(background, bg_scratch, sizeof *background);
    }
done:
    free(bg_scratch);
    free(scratch);
    free(buf);
    return st;
}

/* Writes all of buf; -1 with errno on failure. */
static int write_all(int fd, const uint8_t *buf, size_t len)
{
    size_t done = 0;
    while (done < len) {
        const ssize_t n = write(fd, buf + done, len - done);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            return -1;
        }
        done += (size_t)n;
    }
    return 0;
}

/* Directory part of path ("." when there is none) into dir[cap]. */
static void dir_of(const char *path, char *dir, size_t cap)
{
    const char *slash = strrchr(path, '/');
    if (slash == NULL) {
        snprintf(dir, cap, ".");
    } else if (slash == path) {
        snprintf(dir, cap, "/");
    } else {
        snprintf(dir, cap, "%.*s", (int)(slash - path), path);
    }
}

gmmrrt_status_t gmmrrt_model_save_file(const char *path, const gmmrrt_model_t *model, char *err,
                                       size_t errcap)
{
    return gmmrrt_model_save_file_provenance(path, model, NULL, 0, err, errcap);
}

gmmrrt_status_t gmmrrt_model_save_file_provenance(const char *path, const gmmrrt_model_t *model, const char *text,
                                                  size_t text_len, char *err, size_t errcap)
{
    return gmmrrt_model_save_file_background(path, model, NULL, text, text_len, err, errcap);
}

gmmrrt_status_t gmmrrt_model_save_file_background(const char *path, const gmmrrt_model_t *model,
                                                  const gmmrrt_model_t *background, const char *text, size_t text_len,
                                                  char *err, size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (path == NULL || model == NULL)
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "model path or model is NULL");
    if (path[0] == '\0')
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "model path is empty");

    /* The rename below would replace whatever is at path: a device node, FIFO or directory
     * there (or behind a symbolic link) is someone else's, never a model to overwrite. */
    struct stat existing;
    if (stat(path, &existing) == 0 && !S_ISREG(existing.st_mode))
        return gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap,
                                "%s: not written: it exists and is not a regular file (a device, FIFO, "
                                "directory or a link to one); give a file name",
                                path);

    const size_t cap = gmmrrt_model_max_file_size();
    uint8_t *buf = malloc(cap);
    const size_t tmp_cap = strlen(path) + sizeof ".tmp.XXXXXX";
    char *tmp = malloc(tmp_cap);
    char *dir = malloc(tmp_cap);
    gmmrrt_status_t st = GMMRRT_OK;
    int fd = -1;
    int tmp_exists = 0;
    if (buf == NULL || tmp == NULL || dir == NULL) {
        st = gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: out of memory writing the model", path);
        goto done;
    }

    size_t len = 0;
    char why[256];
    st = gmmrrt_model_encode_file(model, background, text, text_len, buf, cap, &len, why, sizeof why);
    if (st != GMMRRT_OK) {
        gmmrrt_set_error(st, err, errcap, "%s: not written, the model, its background or its provenance is invalid: %s",
                         path, why);
        goto done;
    }

    snprintf(tmp, tmp_cap, "%s.tmp.XXXXXX", path);
    fd = mkstemp(tmp);
    if (fd < 0) {
        st = gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap,
                              "%s: cannot create a temporary file next to it: %s", path, strerror(errno));
        goto done;
    }
    tmp_exists = 1;
    if (fchmod(fd, 0644) != 0 || write_all(fd, buf, len) != 0 || fsync(fd) != 0) {
        st = gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: cannot write %s: %s", path, tmp,
                              strerror(errno));
        goto done;
    }
    const int close_rc = close(fd);
    fd = -1;
    if (close_rc != 0) {
        st = gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: cannot close %s: %s", path, tmp,
                              strerror(errno));
        goto done;
    }
    if (rename(tmp, path) != 0) {
        st = gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: cannot rename %s over it: %s", path, tmp,
                              strerror(errno));
        goto done;
    }
    tmp_exists = 0;
    /* Make the rename itself durable; failing here does not undo a complete file. */
    dir_of(path, dir, tmp_cap);
    const int dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        (void)fsync(dfd);
        close(dfd);
    }
done:
    if (fd >= 0)
        close(fd);
    if (tmp_exists)
        unlink(tmp);
    free(dir);
    free(tmp);
    free(buf);
    return st;
}
