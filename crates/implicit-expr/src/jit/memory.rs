//! Executable memory for compiled tapes, never writable and executable through one
//! address: chunks of a memory file mapped twice, once writable (where code is copied in)
//! and once executable (where it runs). Codes are placed one after another in the current
//! chunk, so that compiling a tape costs no system call but when a chunk fills. When the
//! last code in a chunk is dropped, the chunk is kept for reuse (its pages already mapped:
//! a render compiles thousands of short-lived pruned tapes) up to [`SPARE`] of them, and
//! unmapped beyond.
//!
//! The mappings are shared, so a forked child sees the same pages as its parent: each side
//! counts the fork (an epoch), and no chunk of an earlier epoch is written again, by either
//! side (its codes run on, in both, as they were).
//!
//! Tools that translate machine code as it runs must be told that code is rewritten: a
//! reused chunk is written through the other mapping (valgrind: `--smc-check=all`).

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, Once};

/// The size of a chunk (a larger code gets a chunk of its own).
const CHUNK: usize = 1 << 18;

/// Empty chunks kept for reuse at most.
const SPARE: usize = 64;

/// Code start alignment (the constant pools inside are 16-byte aligned from the start).
const ALIGN: usize = 16;

/// Forks this process has been through, as parent or child.
static EPOCH: AtomicU64 = AtomicU64::new(0);

/// Registers the fork handlers once.
static AT_FORK: Once = Once::new();

/// Counts a fork (run by the C library in the parent and in the child).
extern "C" fn forked() {
    EPOCH.fetch_add(1, Ordering::SeqCst);
}

/// The current epoch.
fn epoch() -> u64 {
    EPOCH.load(Ordering::SeqCst)
}

/// One memory file mapped writable at `rw` and executable at `rx`, in fork epoch `epoch`.
struct Chunk {
    rw: *mut u8,
    rx: *const u8,
    len: usize,
    epoch: u64,
}

// SAFETY: the views are plain memory; writes go only to bytes no code handed out covers,
// under the `CURRENT` lock.
unsafe impl Send for Chunk {}
// SAFETY: as above.
unsafe impl Sync for Chunk {}

impl Chunk {
    /// A chunk of `len` bytes (a multiple of the page size), `None` where the system
    /// refuses.
    fn new(len: usize) -> Option<Self> {
        AT_FORK.call_once(|| {
            // SAFETY: registers a handler that only increments an atomic counter.
            let ok = unsafe { libc::pthread_atfork(None, Some(forked), Some(forked)) } == 0;
            if !ok {
                // Without the handlers a child could not tell: no chunk is ever reused.
                EPOCH.store(u64::MAX, Ordering::SeqCst);
            }
        });
        if epoch() == u64::MAX {
            return None;
        }
        // SAFETY: plain system calls on a descriptor this function owns; every result is
        // checked, and what was made is undone on failure.
        unsafe {
            let fd = libc::memfd_create(c"implicit-expr-jit".as_ptr(), libc::MFD_CLOEXEC);
            if fd < 0 {
                return None;
            }
            let map = |prot| {
                let flags = libc::MAP_SHARED | libc::MAP_POPULATE;
                let p = libc::mmap(std::ptr::null_mut(), len, prot, flags, fd, 0);
                (p != libc::MAP_FAILED).then_some(p)
            };
            let made = if libc::ftruncate(fd, len as libc::off_t) == 0 {
                let rw = map(libc::PROT_READ | libc::PROT_WRITE);
                let rx = map(libc::PROT_READ | libc::PROT_EXEC);
                match (rw, rx) {
                    (Some(rw), Some(rx)) => Some(Chunk {
                        rw: rw.cast(),
                        rx: rx.cast(),
                        len,
                        epoch: epoch(),
                    }),
                    (rw, rx) => {
                        for p in [rw, rx].into_iter().flatten() {
                            libc::munmap(p, len);
                        }
                        None
                    }
                }
            } else {
                None
            };
            // The mappings keep the file.
            libc::close(fd);
            made
        }
    }
}

impl Chunk {
    /// Unmaps both views.
    fn unmap(self) {
        // SAFETY: the two mappings made in `new`, unmapped once (`self` is consumed), when
        // no code in them is left.
        unsafe {
            libc::munmap(self.rw.cast(), self.len);
            libc::munmap(self.rx.cast_mut().cast(), self.len);
        }
    }
}

/// A chunk in use: given back to [`SPARES`] (or unmapped) when the last code in it is
/// dropped (every `ExecMemory` holds it).
struct InUse(Option<Chunk>);

impl Drop for InUse {
    fn drop(&mut self) {
        let Some(chunk) = self.0.take() else { return };
        let mut spares = SPARES.lock().unwrap_or_else(|e| e.into_inner());
        if chunk.len == CHUNK && chunk.epoch == epoch() && spares.len() < SPARE {
            spares.push(chunk);
        } else {
            drop(spares);
            chunk.unmap();
        }
    }
}

/// The chunk new code goes to, and how much of it is used.
static CURRENT: Mutex<Option<(Arc<InUse>, usize)>> = Mutex::new(None);

/// Empty chunks for reuse.
static SPARES: Mutex<Vec<Chunk>> = Mutex::new(Vec::new());

/// A piece of executable memory holding one code.
pub(super) struct ExecMemory {
    chunk: Arc<InUse>,
    offset: usize,
}

impl ExecMemory {
    /// `bytes` copied into executable memory; `None` where the system refuses.
    pub(super) fn new(bytes: &[u8]) -> Option<Self> {
        let need = bytes.len().div_ceil(ALIGN) * ALIGN;
        let mut current = CURRENT.lock().unwrap_or_else(|e| e.into_inner());
        let now = epoch();
        let fits = current.as_ref().is_some_and(|(c, used)| {
            c.0.as_ref()
                .is_some_and(|c| c.epoch == now && used + need <= c.len)
        });
        if !fits {
            let spare = if need <= CHUNK {
                let mut spares = SPARES.lock().unwrap_or_else(|e| e.into_inner());
                // Chunks from before a fork are shared with the other process: unmapped.
                while let Some(old) = spares.pop_if(|c| c.epoch != now) {
                    old.unmap();
                }
                spares.pop()
            } else {
                None
            };
            let chunk = match spare {
                Some(c) => c,
                None => Chunk::new(CHUNK.max(need.div_ceil(4096) * 4096))?,
            };
            *current = Some((Arc::new(InUse(Some(chunk))), 0));
        }
        let (chunk, used) = current.as_mut()?;
        let offset = *used;
        let rw = chunk.0.as_ref()?.rw;
        // SAFETY: `offset + bytes.len() ≤ len`, and no code handed out covers these bytes.
        unsafe {
            std::ptr::copy_nonoverlapping(bytes.as_ptr(), rw.add(offset), bytes.len());
        }
        *used += need;
        Some(Self {
            chunk: chunk.clone(),
            offset,
        })
    }

    /// The address of the first byte, in the executable view.
    pub(super) fn as_ptr(&self) -> *const u8 {
        let rx = self.chunk.0.as_ref().map_or(std::ptr::null(), |c| c.rx);
        // SAFETY: `offset` lies inside the chunk, which is in use while `self` lives.
        unsafe { rx.add(self.offset) }
    }
}
