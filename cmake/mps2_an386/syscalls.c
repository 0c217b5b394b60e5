/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Minimal newlib system calls for test images on qemu mps2-an386: console
 * output and exit through semihosting, a heap for stdio buffers, and stubs
 * for the rest. (newlib's own rdimon startup printed nothing on this board.)
 */
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <sys/stat.h>

#include "semihost.h"

#define CHUNK 64

extern char __heap_start__[], __heap_end__[];

void _exit(int code);
int _write(int fd, const void *buf, size_t len);
int _read(int fd, void *buf, size_t len);
void *_sbrk(ptrdiff_t incr);
int _close(int fd);
int _fstat(int fd, struct stat *st);
int _isatty(int fd);
long _lseek(int fd, long offset, int whence);
int _kill(int pid, int sig);
int _getpid(void);

void _exit(int code)
{
    /* A status that does not fit in 8 bits must not wrap to "passed". */
    if (code < 0 || code > 255) {
        code = 255;
    }
    semihost_exit(code);
    for (;;) {
    }
}

/* stdout and stderr both go to the semihosting console (qemu's stderr),
 * as NUL-terminated chunks for SYS_WRITE0; NUL bytes are dropped. */
int _write(int fd, const void *buf, size_t len)
{
    const char *p = buf;
    char chunk[CHUNK + 1];
    size_t i = 0;

    if (fd != 1 && fd != 2) {
        errno = EBADF;
        return -1;
    }
    while (i < len) {
        size_t n = 0;
        while (n < CHUNK && i < len) {
            char c = p[i++];
            if (c != '\0') {
                chunk[n++] = c;
            }
        }
        chunk[n] = '\0';
        semihost_write0(chunk);
    }
    return (int)len;
}

int _read(int fd, void *buf, size_t len)
{
    (void)fd;
    (void)buf;
    (void)len;
    return 0; /* no input: end of file */
}

/* Heap between the end of .bss and the stack (see the linker script). */
void *_sbrk(ptrdiff_t incr)
{
    static char *top = __heap_start__;
    char *prev = top;

    if (incr > __heap_end__ - top || incr < __heap_start__ - top) {
        errno = ENOMEM;
        return (void *)-1;
    }
    top += incr;
    return prev;
}

int _close(int fd)
{
    (void)fd;
    errno = EBADF;
    return -1;
}

/* The console is a character device, so newlib line-buffers stdout. */
int _fstat(int fd, struct stat *st)
{
    if (fd < 0 || fd > 2) {
        errno = EBADF;
        return -1;
    }
    memset(st, 0, sizeof *st);
    st->st_mode = S_IFCHR;
    return 0;
}

int _isatty(int fd)
{
    return (fd >= 0 && fd <= 2) ? 1 : 0;
}

long _lseek(int fd, long offset, int whence)
{
    (void)fd;
    (void)offset;
    (void)whence;
    errno = ESPIPE;
    return -1;
}

/* raise()/abort() end up here: leave with a failing status. */
int _kill(int pid, int sig)
{
    (void)pid;
    _exit(128 + sig);
    return -1;
}

int _getpid(void)
{
    return 1;
}
