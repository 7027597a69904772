/*
 * alloc_counter.h - counts heap calls, to prove that planning allocates nothing (STYLE.md rule 1).
 *
 * Include in exactly ONE translation unit of an executable: it defines malloc, calloc, realloc,
 * free, aligned_alloc and posix_memalign over glibc's __libc_* entry points, so every heap call
 * in the process (C++ operator new in libstdc++ ends in malloc, so FCL is covered too) passes
 * through here. While `counting` is non-zero each call increments `alloc_calls`.
 * Used by the planner.alloc test and by gmmrrt-bench-memory.
 */
#ifndef GMMRRT_TEST_ALLOC_COUNTER_H
#define GMMRRT_TEST_ALLOC_COUNTER_H

#include <stddef.h>

static volatile int counting;
static volatile long alloc_calls;

extern void *__libc_malloc(size_t);
extern void *__libc_calloc(size_t, size_t);
extern void *__libc_realloc(void *, size_t);
extern void *__libc_memalign(size_t, size_t);
extern void __libc_free(void *);

void *malloc(size_t n)
{
    if (counting)
        ++alloc_calls;
    return __libc_malloc(n);
}
void *calloc(size_t n, size_t m)
{
    if (counting)
        ++alloc_calls;
    return __libc_calloc(n, m);
}
void *realloc(void *p, size_t n)
{
    if (counting)
        ++alloc_calls;
    return __libc_realloc(p, n);
}
void *aligned_alloc(size_t a, size_t n)
{
    if (counting)
        ++alloc_calls;
    return __libc_memalign(a, n);
}
int posix_memalign(void **out, size_t a, size_t n)
{
    if (counting)
        ++alloc_calls;
    *out = __libc_memalign(a, n);
    return *out ? 0 : 12;
}
void free(void *p)
{
    if (counting && p)
        ++alloc_calls;
    __libc_free(p);
}

#endif /* GMMRRT_TEST_ALLOC_COUNTER_H */
