//! How the process keeps freed memory: the shell's Newton iterations allocate and free
//! tangents and band factors of 1-2 MB many thousands of times per point. With glibc's
//! defaults each such block is returned to the kernel when freed (mmap'd, or trimmed off
//! the heap's top) and faulted in again, zeroed, when allocated next (the page faults and
//! their cost measured in docs/tuning.md, "Memory"). Blocks up to 32 MiB are served from
//! the heap instead, and the heap is trimmed only past 512 MiB free. The results do not
//! change, only where their memory comes from.

/// Sets the allocator's thresholds (glibc on Linux; elsewhere nothing to do).
pub fn keep_freed_blocks() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        // Safety: mallopt only changes the allocator's parameters; it is called before
        // any thread is started. A value it refuses leaves the default (return 0).
        unsafe {
            libc::mallopt(libc::M_MMAP_THRESHOLD, 32 << 20);
            libc::mallopt(libc::M_TRIM_THRESHOLD, 512 << 20);
        }
    }
}
