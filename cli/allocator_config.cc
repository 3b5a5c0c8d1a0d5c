// The pqlayout executable's malloc: jemalloc (libjemalloc-dev), configured here, linked into the
// executable only (cli/CMakeLists.txt; base/allocator.h says which malloc a process has).
//
// Why: on a million-triangle reference a fifth of the run's CPU time went to page faults (perf:
// exc_page_fault 20 %, kernel page clearing and the hypervisor's interrupt toggling under it).
// glibc's malloc hands every block above its mmap threshold (128 KiB, rising to 32 MiB) to a fresh
// mmap and unmaps it on free, so each large vector, mesh property and sparse matrix is faulted in
// again, 4 KiB at a time. jemalloc keeps freed extents for reuse (dirty pages decay after 10 s) and
// with thp:always asks for transparent huge pages on them (madvise; the kernel's default policy
// "madvise" then backs them with 2 MiB pages). Measured, 962k triangles to `--until guidance`:
// 311k → 15k minor faults, system time 2.9 → 0.9–1.5 s, wall 9.3–10.5 → 6.5–7.1 s, peak 660 →
// 690 MB; the example 5.9–6.0 → 5.4–5.6 s; outputs byte-identical (benchmarks/RESULTS.md,
// "The executable's malloc"). glibc's own tunables (glibc.malloc.hugetlb=1 with high mmap and
// trim thresholds) did as well in time but peaked at 819 MB, and a tunable only takes effect from
// the environment at exec: the program would have to re-execute itself.
// The environment's MALLOC_CONF still overrides this string (jemalloc reads it after this one).

extern "C" {
// jemalloc reads this symbol of the executable, if defined, at its first allocation.
const char* malloc_conf = "thp:always,metadata_thp:always";
}
