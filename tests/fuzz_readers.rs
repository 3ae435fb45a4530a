//! Every reader against mutated valid files: the seed corpus (`seeds`)
//! through a small deterministic mutator (bit flips, interesting bytes and
//! words, inserted and deleted runs, duplicated chunks, truncation, numbers
//! in text replaced by extreme ones), a fixed number of cases per seed. Each
//! case must give a volume whose length matches its dims, or a `Format` /
//! `InvalidArgument` error; never a panic. Memory is capped at 64 MiB
//! (`HYBRID_OCTREE_MAX_MEMORY`) and a counting allocator checks that no case
//! asks for a buffer beyond the cap. `cargo fuzz` runs the same readers for
//! longer (`fuzz/`).

mod seeds;

use hybrid_octree::io::{read_volume_bytes, ReadOptions};
use hybrid_octree::points::storage::from_bytes;
use hybrid_octree::{Error, Result};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator, remembering the largest single request.
struct Counting;

static LARGEST: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.fetch_max(new_size, Ordering::Relaxed);
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

const CAP: &str = "64M";
const CAP_BYTES: usize = 64 << 20;
/// Mutated cases per seed.
const CASES: usize = 100_000;

fn cap_memory() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| std::env::set_var(hybrid_octree::limits::MAX_MEMORY_VAR, CAP));
}

/// xorshift64*: the same cases on every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const INTERESTING_BYTES: [u8; 8] = [0, 1, 0x7f, 0x80, 0xff, b' ', b'\n', b'-'];
const INTERESTING_WORDS: [u64; 8] = [0, 1, u32::MAX as u64, 0x7fff_ffff, 1 << 31, 1 << 40, u64::MAX, 348];
const EXTREME_NUMBERS: [&str; 10] =
    ["0", "-1", "4294967296", "99999999999999999999", "nan", "-inf", "1e308", "65535", "2147483647", "1.5"];

/// One mutation of `bytes`.
fn mutate_once(bytes: &mut Vec<u8>, rng: &mut Rng) {
    let len = bytes.len();
    match rng.below(9) {
        0 if len > 0 => {
            let i = rng.below(len);
            bytes[i] ^= 1 << rng.below(8);
        }
        1 if len > 0 => {
            let i = rng.below(len);
            bytes[i] = INTERESTING_BYTES[rng.below(INTERESTING_BYTES.len())];
        }
        2 if len >= 8 => {
            let i = rng.below(len - 7);
            let w = INTERESTING_WORDS[rng.below(INTERESTING_WORDS.len())].to_le_bytes();
            let n = if rng.below(2) == 0 { 4 } else { 8 };
            bytes[i..i + n].copy_from_slice(&w[..n]);
        }
        3 => {
            let i = rng.below(len + 1);
            let run = vec![rng.next() as u8; 1 + rng.below(16)];
            bytes.splice(i..i, run);
        }
        4 if len > 0 => {
            let i = rng.below(len);
            let n = 1 + rng.below((len - i).min(64));
            bytes.drain(i..i + n);
        }
        5 if len > 0 => {
            let i = rng.below(len);
            let n = 1 + rng.below((len - i).min(256));
            let chunk = bytes[i..i + n].to_vec();
            let at = rng.below(len + 1);
            bytes.splice(at..at, chunk);
        }
        6 => bytes.truncate(rng.below(len + 1)),
        _ => replace_number(bytes, rng),
    }
}

/// Replaces a run of digits (a count, a size, a value in text) with an extreme number.
fn replace_number(bytes: &mut Vec<u8>, rng: &mut Rng) {
    let digits: Vec<usize> = (0..bytes.len()).filter(|&i| bytes[i].is_ascii_digit()).collect();
    if digits.is_empty() {
        return;
    }
    let start = digits[rng.below(digits.len())];
    let end = (start..bytes.len()).find(|&i| !bytes[i].is_ascii_digit() && bytes[i] != b'.').unwrap_or(bytes.len());
    let number = EXTREME_NUMBERS[rng.below(EXTREME_NUMBERS.len())];
    bytes.splice(start..end, number.bytes());
}

/// Mutated copies of `seed`: one to four mutations each.
fn cases(seed: &[u8], salt: u64) -> impl Iterator<Item = Vec<u8>> + '_ {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15 ^ salt.wrapping_mul(0x1000_0000_01B3));
    (0..CASES).map(move |_| {
        let mut bytes = seed.to_vec();
        for _ in 0..1 + rng.below(4) {
            mutate_once(&mut bytes, &mut rng);
        }
        bytes
    })
}

/// The verdict on one case: a consistent volume (true) or an expected error
/// kind (false).
fn check_volume(result: Result<hybrid_octree::volume::Volume>, what: &str) -> bool {
    match result {
        Ok(v) => {
            assert_eq!(v.samples.len(), v.shape.point_count() * v.components, "{what}: inconsistent volume");
            true
        }
        Err(Error::Format { .. } | Error::InvalidArgument(_)) => false,
        Err(e) => panic!("{what}: unexpected error kind {e:?}"),
    }
}

/// Runs every case of `target`'s seeds through `read` (true: read, false:
/// refused) under catch_unwind. Every seed must read; some cases must too,
/// or the mutations would test only the first check.
fn fuzz(target: &str, read: impl Fn(&str, &[u8]) -> bool + std::panic::RefUnwindSafe) {
    cap_memory();
    let (mut total, mut read_ok) = (0, 0);
    for (n, seed) in seeds::seeds().into_iter().filter(|s| s.target == target).enumerate() {
        assert!(read(seed.name, &seed.bytes), "{target}: the seed {} does not read", seed.name);
        for (i, case) in cases(&seed.bytes, n as u64 + target.len() as u64).enumerate() {
            let Ok(ok) = std::panic::catch_unwind(|| read(seed.name, &case)) else {
                let path = std::env::temp_dir().join(format!("fuzz-crash-{target}-{i}-{}", seed.name));
                std::fs::write(&path, &case).unwrap();
                panic!("{target}: a mutation of {} panicked; the case is in {}", seed.name, path.display());
            };
            total += 1;
            read_ok += usize::from(ok);
        }
    }
    assert!(total >= CASES, "{target}: only {total} cases");
    assert!(read_ok > total / 100 && read_ok < total, "{target}: {read_ok} of {total} mutated cases read");
    eprintln!("{target}: {total} cases, {read_ok} read, the rest refused");
    let largest = LARGEST.load(Ordering::Relaxed);
    assert!(largest <= CAP_BYTES + (1 << 20), "{target}: a buffer of {largest} bytes was allocated");
}

fn read_file(name: &str, bytes: &[u8]) -> bool {
    check_volume(read_volume_bytes(name, bytes, &ReadOptions::default()), name)
}

#[test]
fn vti_reader_survives_mutations() {
    fuzz("vti", read_file);
}

#[test]
fn legacy_vtk_reader_survives_mutations() {
    fuzz("vtk", read_file);
}

#[test]
fn nifti_reader_survives_mutations() {
    fuzz("nifti", read_file);
}

#[test]
fn tiff_reader_survives_mutations() {
    fuzz("tiff", read_file);
}

#[test]
fn raw_reader_survives_mutations() {
    fuzz("raw", |name, bytes| {
        seeds::raw_layout(bytes).is_some_and(|(raw, data)| {
            check_volume(read_volume_bytes(name, data, &ReadOptions { raw: Some(raw) }), name)
        })
    });
}

#[test]
fn hopoints_reader_survives_mutations() {
    fuzz("hopoints", |name, bytes| match from_bytes(bytes, name) {
        Ok(set) => {
            assert!(set.points.iter().all(|p| (0..3).all(|a| usize::from(p.ijk[a]) < set.dims[a])));
            true
        }
        Err(Error::Format { .. }) => false,
        Err(e) => panic!("unexpected error kind {e:?}"),
    });
}

/// Writes the seed corpus to `fuzz/seeds/<target>/` for `cargo fuzz`.
#[test]
#[ignore = "writes files into the source tree; run by hand"]
fn write_seed_corpus() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/seeds");
    for target in seeds::TARGETS {
        std::fs::create_dir_all(root.join(target)).unwrap();
    }
    for seed in seeds::seeds() {
        std::fs::write(root.join(seed.target).join(seed.name), &seed.bytes).unwrap();
    }
}
