/*
 * memory.c: whether a big job fits in the memory this process may still
 * use, so that a mesh too large is refused with a message up front rather
 * than failing half-way (or being killed by the system) after minutes of
 * work.
 */
#include "stages.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

/* MemAvailable from /proc/meminfo (Linux), in bytes; SIZE_MAX when unknown. */
static size_t system_available(void)
{
    FILE *file = fopen("/proc/meminfo", "r");
    if (!file) {
        long pages = sysconf(_SC_AVPHYS_PAGES), size = sysconf(_SC_PAGESIZE);
        return pages > 0 && size > 0 ? (size_t)pages * (size_t)size : SIZE_MAX;
    }
    char line[256];
    size_t available = SIZE_MAX;
    unsigned long long kilobytes;
    while (fgets(line, sizeof line, file))
        if (sscanf(line, "MemAvailable: %llu kB", &kilobytes) == 1) {
            available = (size_t)kilobytes * 1024;
            break;
        }
    fclose(file);
    return available;
}

/* What the address-space limit (ulimit -v) leaves this process; SIZE_MAX when none. */
static size_t limit_left(void)
{
    struct rlimit limit;
    if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY)
        return SIZE_MAX;
    size_t used = 0;
    FILE *file = fopen("/proc/self/statm", "r");
    unsigned long pages;
    if (file) {
        if (fscanf(file, "%lu", &pages) == 1)
            used = (size_t)pages * (size_t)sysconf(_SC_PAGESIZE);
        fclose(file);
    }
    return limit.rlim_cur > used ? (size_t)(limit.rlim_cur - used) : 0;
}

static double gigabytes(size_t bytes)
{
    return (double)bytes / (1024.0 * 1024.0 * 1024.0);
}

ur_status job_check_memory(const job_run *run, const char *what, size_t needed)
{
    size_t system = system_available(), limit = limit_left();
    size_t available = system < limit ? system : limit;
    if (available == SIZE_MAX || needed <= available)
        return UR_OK;
    return job_fail(run, UR_ERROR_MEMORY,
                    "%s: %s needs about %.2f GB of memory, but only %.2f GB is available%s",
                    run->job.command, what, gigabytes(needed), gigabytes(available),
                    limit < system ? " under this process's limit (ulimit -v)" : "");
}
