/* planner.model_file: reading and atomically writing model files (model_file.h).
 * Round trip through a file; unreadable, missing, oversized and corrupt files each give
 * their status and leave the caller's model untouched; a failed save leaves no file and
 * no temporary file behind, and never damages the file it would have replaced. */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cmocka.h>

#include "gmmrrt/model_file.h"
#include "model_fixture.h"

typedef struct {
    char dir[256];
    char path[320];
} sandbox_t;

static int setup(void **state)
{
    sandbox_t *s = calloc(1, sizeof *s);
    if (s == NULL)
        return -1;
    snprintf(s->dir, sizeof s->dir, "%s/gmmrrt-model-file-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (mkdtemp(s->dir) == NULL)
        return -1;
    snprintf(s->path, sizeof s->path, "%s/avoid.gmm", s->dir);
    *state = s;
    return 0;
}

static int teardown(void **state)
{
    sandbox_t *s = *state;
    DIR *d = opendir(s->dir);
    if (d != NULL) {
        struct dirent *e;
        char p[600];
        while ((e = readdir(d)) != NULL) {
            if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
                continue;
            snprintf(p, sizeof p, "%s/%s", s->dir, e->d_name);
            unlink(p);
        }
        closedir(d);
    }
    rmdir(s->dir);
    free(s);
    return 0;
}

/* Number of entries in dir (without . and ..). */
static int count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    assert_non_null(d);
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0)
            ++n;
    closedir(d);
    return n;
}

static void write_bytes(const char *path, const uint8_t *buf, size_t len)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(buf, 1, len, f), len);
    assert_int_equal(fclose(f), 0);
}

static size_t read_bytes(const char *path, uint8_t *buf, size_t cap)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    const size_t n = fread(buf, 1, cap, f);
    fclose(f);
    return n;
}

static void test_save_then_load_round_trips(void **state)
{
    sandbox_t *s = *state;
    gmmrrt_model_t m, back;
    fixture_features_model(&m);
    char err[512];
    assert_int_equal(gmmrrt_model_save_file(s->path, &m, err, sizeof err), GMMRRT_OK);
    assert_int_equal(count_entries(s->dir), 1);
    struct stat sb;
    assert_int_equal(stat(s->path, &sb), 0);
    assert_int_equal(sb.st_mode & 0777, 0644);
    assert_int_equal((size_t)sb.st_size, gmmrrt_model_encoded_size(2, 3));
    memset(&back, 0, sizeof back);
    assert_int_equal(gmmrrt_model_load_file(s->path, &back, err, sizeof err), GMMRRT_OK);
    assert_memory_equal(back.weight, m.weight, sizeof m.weight);
    assert_memory_equal(back.mean, m.mean, sizeof m.mean);
    assert_memory_equal(back.chol, m.chol, sizeof m.chol);
    assert_int_equal(back.kind, m.kind);
    assert_true(back.cum_weight[2] == 1.0); /* prepared */
    /* The bytes on disk are exactly the encoder's. */
    uint8_t want[256], got[256];
    size_t len = 0;
    assert_int_equal(gmmrrt_model_encode(&m, want, sizeof want, &len, err, sizeof err), GMMRRT_OK);
    assert_int_equal(read_bytes(s->path, got, sizeof got), len);
    assert_memory_equal(got, want, len);
}

static void test_missing_file_is_io_error_naming_path_and_reason(void **state)
{
    sandbox_t *s = *state;
    gmmrrt_model_t m, before;
    fixture_features_model(&m);
    before = m;
    char err[512];
    assert_int_equal(gmmrrt_model_load_file(s->path, &m, err, sizeof err), GMMRRT_ERR_IO);
    assert_non_null(strstr(err, s->path));
    assert_non_null(strstr(err, strerror(ENOENT)));
    assert_memory_equal(&m, &before, sizeof m);
    assert_int_equal(gmmrrt_model_load_file(s->dir, &m, err, sizeof err), GMMRRT_ERR_IO);
    assert_non_null(strstr(err, "directory"));
    assert_memory_equal(&m, &before, sizeof m);
    assert_int_equal(gmmrrt_model_load_file(NULL, &m, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
}

static void test_oversized_file_is_too_large_and_model_untouched(void **state)
{
    sandbox_t *s = *state;
    const size_t max = gmmrrt_model_max_file_size();
    const size_t big_len = 10 * max;
    uint8_t *big = calloc(big_len, 1);
    assert_non_null(big);
    gmmrrt_model_t m, before;
    fixture_features_model(&m);
    size_t len = 0;
    char err[512];
    assert_int_equal(gmmrrt_model_encode(&m, big, big_len, &len, err, sizeof err), GMMRRT_OK);
    write_bytes(s->path, big, big_len); /* a valid model followed by lots of zeros */
    assert_int_equal(gmmrrt_model_prepare(&m, NULL, 0), GMMRRT_OK);
    before = m;
    assert_int_equal(gmmrrt_model_load_file(s->path, &m, err, sizeof err), GMMRRT_ERR_MODEL_TOO_LARGE);
    assert_non_null(strstr(err, s->path));
    assert_memory_equal(&m, &before, sizeof m);
    /* Exactly one byte too many is also too large; exactly the maximum is not. */
    write_bytes(s->path, big, max + 1);
    assert_int_equal(gmmrrt_model_load_file(s->path, &m, err, sizeof err), GMMRRT_ERR_MODEL_TOO_LARGE);
    write_bytes(s->path, big, max);
    assert_int_equal(gmmrrt_model_load_file(s->path, &m, err, sizeof err), GMMRRT_ERR_MODEL_BAD_SIZE);
    assert_memory_equal(&m, &before, sizeof m);
    free(big);
}

static void test_corrupt_and_empty_files_keep_the_model(void **state)
{
    sandbox_t *s = *state;
    gmmrrt_model_t m, other, before;
    fixture_features_model(&m);
    fixture_generic_d4_model(&other);
    assert_int_equal(gmmrrt_model_prepare(&other, NULL, 0), GMMRRT_OK);
    char err[512];
    assert_int_equal(gmmrrt_model_save_file(s->path, &m, err, sizeof err), GMMRRT_OK);
    uint8_t buf[256];
    const size_t len = read_bytes(s->path, buf, sizeof buf);
    buf[40] ^= 0x01;
    write_bytes(s->path, buf, len);
    before = other;
    assert_int_equal(gmmrrt_model_load_file(s->path, &other, err, sizeof err), GMMRRT_ERR_MODEL_BAD_CHECKSUM);
    assert_non_null(strstr(err, "CRC"));
    assert_memory_equal(&other, &before, sizeof other);
    write_bytes(s->path, buf, 0);
    assert_int_equal(gmmrrt_model_load_file(s->path, &other, err, sizeof err), GMMRRT_ERR_MODEL_TRUNCATED);
    assert_memory_equal(&other, &before, sizeof other);
}

static void test_failed_save_leaves_no_file_and_keeps_the_old_one(void **state)
{
    sandbox_t *s = *state;
    gmmrrt_model_t good, bad;
    fixture_features_model(&good);
    char err[512];
    /* Invalid model: nothing written at all. */
    bad = good;
    bad.chol[1][2] = -1.0;
    assert_int_equal(gmmrrt_model_save_file(s->path, &bad, err, sizeof err), GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE);
    assert_non_null(strstr(err, "component 1"));
    assert_int_equal(count_entries(s->dir), 0);
    /* An existing model survives a failed overwrite byte for byte. */
    assert_int_equal(gmmrrt_model_save_file(s->path, &good, err, sizeof err), GMMRRT_OK);
    uint8_t old[256], now[256];
    const size_t old_len = read_bytes(s->path, old, sizeof old);
    assert_int_equal(gmmrrt_model_save_file(s->path, &bad, err, sizeof err), GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE);
    assert_int_equal(read_bytes(s->path, now, sizeof now), old_len);
    assert_memory_equal(now, old, old_len);
    assert_int_equal(count_entries(s->dir), 1);
    /* A directory that does not exist: an I/O error naming the path, nothing created. */
    char missing[400];
    snprintf(missing, sizeof missing, "%s/no-such-dir/m.gmm", s->dir);
    assert_int_equal(gmmrrt_model_save_file(missing, &good, err, sizeof err), GMMRRT_ERR_IO);
    assert_non_null(strstr(err, missing));
    assert_int_equal(count_entries(s->dir), 1);
    /* A directory (or device, FIFO) at the path is refused before anything is written. */
    char subdir[400];
    snprintf(subdir, sizeof subdir, "%s/taken", s->dir);
    assert_int_equal(mkdir(subdir, 0755), 0);
    char inner[480];
    snprintf(inner, sizeof inner, "%s/keep", subdir);
    write_bytes(inner, old, 1); /* non-empty directory: rename(2) cannot replace it */
    assert_int_equal(gmmrrt_model_save_file(subdir, &good, err, sizeof err), GMMRRT_ERR_IO);
    assert_non_null(strstr(err, "not a regular file"));
    assert_non_null(strstr(err, subdir));
    assert_int_equal(count_entries(s->dir), 2); /* avoid.gmm and taken/, no temporary file */
    unlink(inner);
    rmdir(subdir);
    assert_int_equal(gmmrrt_model_save_file(NULL, &good, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_int_equal(gmmrrt_model_save_file("", &good, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_save_then_load_round_trips, setup, teardown),
        cmocka_unit_test_setup_teardown(test_missing_file_is_io_error_naming_path_and_reason, setup, teardown),
        cmocka_unit_test_setup_teardown(test_oversized_file_is_too_large_and_model_untouched, setup, teardown),
        cmocka_unit_test_setup_teardown(test_corrupt_and_empty_files_keep_the_model, setup, teardown),
        cmocka_unit_test_setup_teardown(test_failed_save_leaves_no_file_and_keeps_the_old_one, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
