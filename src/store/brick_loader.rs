//! Bricks read from a store in the background while frames are drawn.
//!
//! A frame asks for the texel lattices its selection needs and is not yet
//! holding ([`BrickLoader::request`], in the order it wants them); one
//! worker thread reads them with [`Store::read_texels`], one at a time, and
//! keeps each read volume until the frame that wants it takes it
//! ([`BrickLoader::take`]). What a newer request no longer names is
//! dropped (queued, read or being read), so the loader holds at most the
//! frame's wanted bricks, and it starts no read while the volumes waiting
//! to be taken hold `memory_bytes` or more: the RAM budget of loaded
//! bricks, the texture budget's counterpart in host memory.
//!
//! A read fails the same way it fails in the frame's own thread: the
//! loader keeps the first failure (a missing or damaged chunk, a panic in
//! the reader), reads nothing more, and [`BrickLoader::failure`] hands it
//! to the next frame.

use super::Store;
use crate::data::volume::Volume;
use std::collections::{HashMap, HashSet, VecDeque};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;

/// A brick's texel lattice as [`Store::read_texels`] reads it: `texels`
/// per axis every `stride` samples from level-0 index `lo`, `border` more
/// on each side.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct BrickRead {
    /// Samples between texels (a power of two).
    pub stride: usize,
    /// The first texel's level-0 index (a multiple of the stride).
    pub lo: [usize; 3],
    /// Texels per axis, the border left out.
    pub texels: [usize; 3],
    /// Texels more on each side.
    pub border: usize,
}

/// What the loader holds and has done.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LoaderStatus {
    /// Requested bricks not read yet (the one being read included).
    pub pending: usize,
    /// Read bricks waiting to be taken, and their bytes.
    pub ready: usize,
    /// Bytes of the read bricks waiting to be taken.
    pub ready_bytes: usize,
    /// Bytes of samples read since the loader started.
    pub bytes_read: u64,
    /// Bricks read since the loader started.
    pub reads: u64,
}

#[derive(Default)]
struct State {
    queue: VecDeque<BrickRead>,
    /// The brick being read, and whether the last request still wants it.
    in_flight: Option<(BrickRead, bool)>,
    ready: HashMap<BrickRead, Volume>,
    ready_bytes: usize,
    memory_bytes: usize,
    failure: Option<String>,
    bytes_read: u64,
    reads: u64,
    stop: bool,
}

struct Shared {
    state: Mutex<State>,
    wake: Condvar,
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The background reader of one open store.
pub struct BrickLoader {
    shared: Arc<Shared>,
    worker: Option<JoinHandle<()>>,
}

impl BrickLoader {
    /// Starts the worker thread reading from `store`.
    ///
    /// # Errors
    ///
    /// The operating system's refusal to start a thread, as a message.
    pub fn start(store: Arc<Store>) -> Result<BrickLoader, String> {
        let shared = Arc::new(Shared { state: Mutex::new(State::default()), wake: Condvar::new() });
        let worker_shared = Arc::clone(&shared);
        let worker = std::thread::Builder::new()
            .name("hybrid-octree-bricks".into())
            .spawn(move || work(&worker_shared, &store))
            .map_err(|e| format!("could not start the brick loading thread: {e}"))?;
        Ok(BrickLoader { shared, worker: Some(worker) })
    }

    /// The bricks a frame wants and does not hold, in the order to read
    /// them: queued unless read or being read already. Bricks of earlier
    /// requests not named here are dropped. No read starts while the bricks
    /// waiting to be taken hold `memory_bytes` or more.
    pub fn request(&self, wanted: &[BrickRead], memory_bytes: usize) {
        let names: HashSet<&BrickRead> = wanted.iter().collect();
        let mut st = self.shared.lock();
        st.memory_bytes = memory_bytes;
        let mut dropped = 0;
        st.ready.retain(|read, volume| {
            let keep = names.contains(read);
            if !keep {
                dropped += volume.samples.as_bytes().len();
            }
            keep
        });
        st.ready_bytes -= dropped;
        if let Some((read, still)) = st.in_flight.as_mut() {
            *still = names.contains(read);
        }
        let flying = st.in_flight.map(|(read, _)| read);
        let queue: VecDeque<BrickRead> =
            wanted.iter().filter(|r| !st.ready.contains_key(*r) && flying.as_ref() != Some(*r)).copied().collect();
        st.queue = queue;
        drop(st);
        self.shared.wake.notify_all();
    }

    /// Whether `read` has been read and waits to be taken.
    pub fn is_ready(&self, read: &BrickRead) -> bool {
        self.shared.lock().ready.contains_key(read)
    }

    /// The read volume of `read`, if it has been read: the loader gives it up.
    pub fn take(&self, read: &BrickRead) -> Option<Volume> {
        let mut st = self.shared.lock();
        let volume = st.ready.remove(read)?;
        st.ready_bytes -= volume.samples.as_bytes().len();
        drop(st);
        self.shared.wake.notify_all();
        Some(volume)
    }

    /// What it holds and has read.
    pub fn status(&self) -> LoaderStatus {
        let st = self.shared.lock();
        LoaderStatus {
            pending: st.queue.len() + usize::from(st.in_flight.is_some()),
            ready: st.ready.len(),
            ready_bytes: st.ready_bytes,
            bytes_read: st.bytes_read,
            reads: st.reads,
        }
    }

    /// The first read that failed, if one did (then nothing more is read).
    pub fn failure(&self) -> Option<String> {
        self.shared.lock().failure.clone()
    }
}

impl Drop for BrickLoader {
    fn drop(&mut self) {
        self.shared.lock().stop = true;
        self.shared.wake.notify_all();
        if let Some(worker) = self.worker.take() {
            // A panic is caught inside the loop: joining only waits for the read in flight.
            let _ = worker.join();
        }
    }
}

/// The worker: the queue's front brick while the budget allows, until stopped.
fn work(shared: &Shared, store: &Store) {
    let mut st = shared.lock();
    loop {
        if st.stop {
            return;
        }
        let room = st.ready_bytes < st.memory_bytes.max(1);
        let next = if st.failure.is_none() && room { st.queue.pop_front() } else { None };
        let Some(read) = next else {
            st = shared.wake.wait(st).unwrap_or_else(|e| e.into_inner());
            continue;
        };
        st.in_flight = Some((read, true));
        drop(st);
        let got = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            store.read_texels(read.stride, read.lo, read.texels, read.border)
        }));
        st = shared.lock();
        let still = st.in_flight.take().is_some_and(|(_, still)| still);
        match got {
            Ok(Ok(volume)) => {
                let bytes = volume.samples.as_bytes().len();
                st.bytes_read += bytes as u64;
                st.reads += 1;
                if still {
                    st.ready_bytes += bytes;
                    st.ready.insert(read, volume);
                }
            }
            Ok(Err(e)) => st.failure = Some(e.to_string()),
            Err(_) => {
                st.failure = Some(format!(
                    "reading the brick of stride {} at {:?} from '{}' panicked (a bug: please report it)",
                    read.stride,
                    read.lo,
                    store.label()
                ))
            }
        }
    }
}
