//! Where finite-bearing tables are kept between uses (docs/physics.md §4, finite bearing): a
//! process cache keyed by (D/L, supply convention), the tables shipped inside the library (the
//! paper's L/D = 2.5, both conventions: [`SHIPPED`]), and a disk cache in the user's cache
//! directory, so that only the first process on a machine ever solves any other table, and only
//! one thread of it.
//!
//! Disk cache: `$CLEARSIM_CACHE_DIR` if set (empty: no disk cache), else `$XDG_CACHE_HOME/clearsim`,
//! else `~/.cache/clearsim` (`%LOCALAPPDATA%\clearsim` on Windows). One file per (D/L, supply,
//! grid, [`SOLVER_VERSION`]), written to a temporary file and renamed into place (atomic), and
//! validated on load (magic, version, key, size, checksum, finite values): a file that fails is
//! rebuilt and rewritten, never trusted. A directory that cannot be written is silently skipped.

use super::bearing_finite::{FiniteBearingTable, ReynoldsGrid, TABLE_EPS_MAX};
use super::geometry::FilmSupply;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Condvar, Mutex, OnceLock};

/// Version of the Reynolds solver and of the table's layout: bump it on any change that alters a
/// table's numbers, so that older cache files are ignored.
pub const SOLVER_VERSION: u32 = 4;

const MAGIC: &[u8; 8] = b"CSFBTAB\0";

/// How a table reached the caller.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TableSource {
    /// Solved in this process (and written to the disk cache if it has one).
    Built,
    /// Read from the disk cache.
    Loaded,
}

static BUILT: AtomicUsize = AtomicUsize::new(0);
static LOADED: AtomicUsize = AtomicUsize::new(0);

/// Tables solved and tables loaded from disk by this process so far (for tests and diagnostics).
pub fn table_counts() -> (usize, usize) {
    (BUILT.load(Ordering::Relaxed), LOADED.load(Ordering::Relaxed))
}

/// The disk cache's directory (module doc), or `None` when there is none.
pub fn cache_dir() -> Option<PathBuf> {
    if let Some(v) = std::env::var_os("CLEARSIM_CACHE_DIR") {
        return if v.is_empty() { None } else { Some(PathBuf::from(v)) };
    }
    if let Some(v) = std::env::var_os("XDG_CACHE_HOME").filter(|v| !v.is_empty()) {
        return Some(PathBuf::from(v).join("clearsim"));
    }
    if cfg!(windows) {
        if let Some(v) = std::env::var_os("LOCALAPPDATA").filter(|v| !v.is_empty()) {
            return Some(PathBuf::from(v).join("clearsim"));
        }
    }
    std::env::var_os("HOME").filter(|v| !v.is_empty()).map(|h| PathBuf::from(h).join(".cache").join("clearsim"))
}

/// Tables shipped inside the library, in the disk cache's format (`encode`): the paper's
/// bearing (L/D = 2.5, k = 2R/L as the nine-bar computes it) under both supply conventions, so
/// that `clearsim paper` solves none on a first run. A test checks them against a fresh solve
/// (`shipped_tables_match_a_fresh_solve`); after a change of the solver (and of
/// [`SOLVER_VERSION`]) regenerate them with
/// `CLEARSIM_WRITE_SHIPPED_TABLES=1 cargo test --release --features python shipped_tables`.
pub const SHIPPED: [(&str, &[u8]); 2] = [
    ("ld2.5_widest_gap.bin", include_bytes!("bearing_finite_tables/ld2.5_widest_gap.bin")),
    ("ld2.5_none.bin", include_bytes!("bearing_finite_tables/ld2.5_none.bin")),
];

/// The shipped table for (k, supply) on the default grid, if one was solved for this k (to 4e-16
/// relative: 2R/L rounds differently for one L/D given by different R and L, a difference 1e8
/// times below the solver's tolerance) with this solver version.
pub fn shipped(k: f64, supply: FilmSupply) -> Option<FiniteBearingTable> {
    SHIPPED.iter().find_map(|(_, bytes)| {
        let k_file = f64::from_le_bytes(bytes.get(12..20)?.try_into().ok()?);
        ((k_file - k).abs() <= 4e-16 * k.abs()).then(|| decode(bytes, k_file, supply, ReynoldsGrid::default()))?
    })
}

/// The keys `table_for` looked up beyond the process cache, in order (for the tests).
#[cfg(test)]
static FETCHED: Mutex<Vec<(u64, FilmSupply)>> = Mutex::new(Vec::new());

/// A table of the process cache: solved (or loaded) already, or being solved by a thread.
#[derive(Clone, Copy)]
enum Slot {
    Ready(&'static FiniteBearingTable),
    Solving(std::thread::ThreadId),
}

/// The table of a bearing with diameter-to-length ratio `k` and supply convention `supply` on the
/// default grid: from this process's cache, else shipped ([`SHIPPED`]), else from the disk cache,
/// else solved (a few seconds on two cores) and stored in both. Kept for the life of the process.
///
/// Solved once: a thread asking for a table another thread is solving waits for it. Except on a
/// thread of rayon's pool (a batch's run), which solves its own copy instead (the first stored
/// wins): the solve itself runs on that pool, so a pool thread waiting for it could hold up the
/// very work it waits for (or, reached again on the solving thread through work stealing, wait
/// for itself).
pub fn table_for(k: f64, supply: FilmSupply) -> &'static FiniteBearingTable {
    type Key = (u64, FilmSupply);
    static CACHE: OnceLock<(Mutex<HashMap<Key, Slot>>, Condvar)> = OnceLock::new();
    let (cache, solved) = CACHE.get_or_init(|| (Mutex::new(HashMap::new()), Condvar::new()));
    let key = (k.to_bits(), supply);
    let me = std::thread::current().id();
    let mut map = cache.lock().unwrap_or_else(|e| e.into_inner());
    loop {
        match map.get(&key).copied() {
            Some(Slot::Ready(t)) => return t,
            Some(Slot::Solving(who)) if who != me && rayon::current_thread_index().is_none() => {
                map = solved.wait(map).unwrap_or_else(|e| e.into_inner());
            }
            Some(Slot::Solving(_)) => break,
            None => {
                map.insert(key, Slot::Solving(me));
                break;
            }
        }
    }
    drop(map);
    // Not holding the lock while solving; if the solve panics, the slot is freed for the next caller.
    struct Release<'a>(&'a Mutex<HashMap<Key, Slot>>, &'a Condvar, Key, std::thread::ThreadId);
    impl Drop for Release<'_> {
        fn drop(&mut self) {
            let mut map = self.0.lock().unwrap_or_else(|e| e.into_inner());
            if matches!(map.get(&self.2), Some(Slot::Solving(who)) if *who == self.3) {
                map.remove(&self.2);
            }
            self.1.notify_all();
        }
    }
    let release = Release(cache, solved, key, me);
    #[cfg(test)]
    FETCHED.lock().unwrap_or_else(|e| e.into_inner()).push(key);
    let table = match shipped(k, supply) {
        Some(t) => t,
        None => load_or_build(cache_dir().as_deref(), k, supply, ReynoldsGrid::default()).0,
    };
    let table: &'static FiniteBearingTable = Box::leak(Box::new(table));
    let mut map = cache.lock().unwrap_or_else(|e| e.into_inner());
    let table = match map.get(&key) {
        Some(Slot::Ready(first)) => *first,
        _ => {
            map.insert(key, Slot::Ready(table));
            table
        }
    };
    drop(map);
    drop(release);
    table
}

/// The table for (k, supply, grid) from the cache directory `dir` if a valid file is there, else
/// solved and written there (silently skipped when `dir` is `None` or cannot be written).
pub fn load_or_build(dir: Option<&Path>, k: f64, supply: FilmSupply, grid: ReynoldsGrid) -> (FiniteBearingTable, TableSource) {
    let path = dir.map(|d| d.join(file_name(k, supply, grid)));
    if let Some(table) = path.as_ref().and_then(|p| std::fs::read(p).ok()).and_then(|b| decode(&b, k, supply, grid)) {
        LOADED.fetch_add(1, Ordering::Relaxed);
        return (table, TableSource::Loaded);
    }
    let table = FiniteBearingTable::build(k, supply, grid);
    BUILT.fetch_add(1, Ordering::Relaxed);
    if let Some(p) = path {
        let _ = write_atomically(&p, &encode(&table));
    }
    (table, TableSource::Built)
}

/// The cache file's name: every part of the key in it.
pub fn file_name(k: f64, supply: FilmSupply, grid: ReynoldsGrid) -> String {
    let s = match supply {
        FilmSupply::WidestGap => "widest_gap",
        FilmSupply::None => "none",
    };
    format!("finite_bearing_v{SOLVER_VERSION}_k{:016x}_{s}_{}x{}.bin", k.to_bits(), grid.n_theta, grid.n_zeta)
}

fn supply_code(supply: FilmSupply) -> u8 {
    match supply {
        FilmSupply::WidestGap => 1,
        FilmSupply::None => 2,
    }
}

/// FNV-1a (64 bit) of `bytes`: enough to catch a truncated or damaged file.
fn checksum(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3))
}

/// Header (key and layout), the values J_ξ, J_η little-endian, then the header+values checksum.
fn encode(t: &FiniteBearingTable) -> Vec<u8> {
    let mut b = Vec::with_capacity(64 + 16 * t.j.len());
    b.extend_from_slice(MAGIC);
    b.extend_from_slice(&SOLVER_VERSION.to_le_bytes());
    b.extend_from_slice(&t.k.to_le_bytes());
    b.push(supply_code(t.supply));
    b.extend_from_slice(&(t.grid.n_theta as u32).to_le_bytes());
    b.extend_from_slice(&(t.grid.n_zeta as u32).to_le_bytes());
    b.extend_from_slice(&t.s_step.to_le_bytes());
    b.extend_from_slice(&TABLE_EPS_MAX.to_le_bytes());
    b.extend_from_slice(&(t.n_s as u32).to_le_bytes());
    b.extend_from_slice(&(t.n_theta_m as u32).to_le_bytes());
    b.extend_from_slice(&(t.centre_rows() as u32).to_le_bytes());
    for (x, y) in t.j.iter().chain(&t.centre) {
        b.extend_from_slice(&x.to_le_bytes());
        b.extend_from_slice(&y.to_le_bytes());
    }
    let sum = checksum(&b);
    b.extend_from_slice(&sum.to_le_bytes());
    b
}

/// The table in `bytes` if it is whole and is the one asked for (same key, layout and version).
fn decode(bytes: &[u8], k: f64, supply: FilmSupply, grid: ReynoldsGrid) -> Option<FiniteBearingTable> {
    let (body, sum) = bytes.split_at_checked(bytes.len().checked_sub(8)?)?;
    if checksum(body) != u64::from_le_bytes(sum.try_into().ok()?) {
        return None;
    }
    let mut r = Reader { b: body };
    if r.take(8)? != MAGIC || r.u32()? != SOLVER_VERSION || r.f64()?.to_bits() != k.to_bits() || r.take(1)?[0] != supply_code(supply) {
        return None;
    }
    if r.u32()? as usize != grid.n_theta || r.u32()? as usize != grid.n_zeta {
        return None;
    }
    let fresh = FiniteBearingTable::layout(k, supply, grid);
    if r.f64()?.to_bits() != fresh.s_step.to_bits() || r.f64()?.to_bits() != TABLE_EPS_MAX.to_bits() {
        return None;
    }
    let (n_main, n_centre) = (fresh.n_s * fresh.n_theta_m, fresh.centre_rows() * fresh.n_theta_m);
    if r.u32()? as usize != fresh.n_s || r.u32()? as usize != fresh.n_theta_m || r.u32()? as usize != fresh.centre_rows() || r.b.len() != 16 * (n_main + n_centre) {
        return None;
    }
    let mut j = Vec::with_capacity(n_main + n_centre);
    while !r.b.is_empty() {
        let (x, y) = (r.f64()?, r.f64()?);
        if !(x.is_finite() && y.is_finite()) {
            return None;
        }
        j.push((x, y));
    }
    let centre = j.split_off(n_main);
    Some(FiniteBearingTable { j, centre, ..fresh })
}

struct Reader<'a> {
    b: &'a [u8],
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let (head, tail) = self.b.split_at_checked(n)?;
        self.b = tail;
        Some(head)
    }
    fn u32(&mut self) -> Option<u32> {
        Some(u32::from_le_bytes(self.take(4)?.try_into().ok()?))
    }
    fn f64(&mut self) -> Option<f64> {
        Some(f64::from_le_bytes(self.take(8)?.try_into().ok()?))
    }
}

/// Write `bytes` to a temporary file beside `path` and rename it into place, so that a reader
/// sees either no file or a whole one.
fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::io::Write;
    let dir = path.parent().ok_or_else(|| std::io::Error::other("no parent directory"))?;
    std::fs::create_dir_all(dir)?;
    let nanos = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.subsec_nanos());
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("table");
    let tmp = dir.join(format!(".{name}.{}.{nanos}.tmp", std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small grid keeps the solves of these tests short.
    const GRID: ReynoldsGrid = ReynoldsGrid { n_theta: 24, n_zeta: 4 };

    fn temp_dir(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("clearsim_cache_test_{tag}_{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn second_use_loads_the_same_numbers_and_a_damaged_file_is_rebuilt() {
        let dir = temp_dir("roundtrip");
        let (fresh, how) = load_or_build(Some(&dir), 2.0, FilmSupply::WidestGap, GRID);
        assert_eq!(how, TableSource::Built);
        let path = dir.join(file_name(2.0, FilmSupply::WidestGap, GRID));
        assert!(path.exists(), "no cache file written");
        // A second process (here: a second call that bypasses the process cache) loads it.
        let (loaded, how) = load_or_build(Some(&dir), 2.0, FilmSupply::WidestGap, GRID);
        assert_eq!(how, TableSource::Loaded);
        assert_eq!(loaded, fresh, "the cache must return the very numbers solved");
        // Another key (supply, k, grid) is another file.
        assert_eq!(load_or_build(Some(&dir), 2.0, FilmSupply::None, GRID).1, TableSource::Built);
        assert_eq!(load_or_build(Some(&dir), 2.5, FilmSupply::WidestGap, GRID).1, TableSource::Built);
        // Truncated, one flipped byte, a wrong key inside a right name, garbage: all rebuilt.
        let good = std::fs::read(&path).unwrap();
        let other = std::fs::read(dir.join(file_name(2.5, FilmSupply::WidestGap, GRID))).unwrap();
        let mut flipped = good.clone();
        flipped[100] ^= 0x10;
        for bad in [good[..good.len() / 2].to_vec(), flipped, other, b"not a table".to_vec(), Vec::new()] {
            std::fs::write(&path, &bad).unwrap();
            let (t, how) = load_or_build(Some(&dir), 2.0, FilmSupply::WidestGap, GRID);
            assert_eq!(how, TableSource::Built);
            assert_eq!(t, fresh);
            assert_eq!(std::fs::read(&path).unwrap(), good, "the rebuilt table is written back");
        }
        // No temporary files are left behind.
        let left: Vec<_> = std::fs::read_dir(&dir).unwrap().filter_map(|e| e.ok()).filter(|e| e.file_name().to_string_lossy().ends_with(".tmp")).collect();
        assert!(left.is_empty());
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// The shipped tables are what the solver gives today: same version, same key, the same
    /// numbers as a fresh solve (bit for bit on the platform that wrote them; 1e-6 of the table's
    /// largest load leaves room for another platform's last-digit sin/exp). With
    /// `CLEARSIM_WRITE_SHIPPED_TABLES=1` it writes them instead (after a solver change).
    #[test]
    fn shipped_tables_match_a_fresh_solve() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("rust/laws/bearing_finite_tables");
        let write = std::env::var_os("CLEARSIM_WRITE_SHIPPED_TABLES").is_some_and(|v| !v.is_empty());
        let mut supplies = Vec::new();
        for (name, bytes) in SHIPPED {
            let k = f64::from_le_bytes(bytes[12..20].try_into().unwrap());
            let supply = if name.contains("widest_gap") { FilmSupply::WidestGap } else { FilmSupply::None };
            let fresh = FiniteBearingTable::build(k, supply, ReynoldsGrid::default());
            if write {
                std::fs::write(dir.join(name), encode(&fresh)).unwrap();
                continue;
            }
            let version = u32::from_le_bytes(bytes[8..12].try_into().unwrap());
            let again = "regenerate: CLEARSIM_WRITE_SHIPPED_TABLES=1 cargo test --release --features python shipped_tables";
            assert_eq!(version, SOLVER_VERSION, "{name} was solved by solver version {version}; {again}");
            let t = shipped(k, supply).unwrap_or_else(|| panic!("{name} does not decode as {supply:?}; {again}"));
            assert_eq!((t.k, t.supply, t.n_s, t.n_theta_m, t.j.len(), t.centre.len()), (fresh.k, fresh.supply, fresh.n_s, fresh.n_theta_m, fresh.j.len(), fresh.centre.len()));
            let scale = fresh.j.iter().chain(&fresh.centre).fold(0.0f64, |m, v| m.max(v.0.hypot(v.1)));
            for (a, b) in t.j.iter().chain(&t.centre).zip(fresh.j.iter().chain(&fresh.centre)) {
                assert!((a.0 - b.0).hypot(a.1 - b.1) <= 1e-6 * scale, "{name}: shipped {a:?}, solved now {b:?}; {again}");
            }
            // The nine-bar's k (2R/L, not exactly 0.4) and 0.4 itself both find it.
            assert!(shipped(0.4, supply).is_some() && shipped(2.0 * 0.02 / 0.1, supply).is_some());
            assert!(shipped(0.4 * (1.0 + 1e-12), supply).is_none());
            supplies.push(supply);
        }
        assert!(write || supplies == [FilmSupply::WidestGap, FilmSupply::None], "{supplies:?}");
    }

    /// Threads asking for one new table at once get the same table, solved once.
    #[test]
    fn concurrent_requests_solve_a_table_once() {
        // B/D = 1/4 without the supply line: the squeeze test asks for it too (maybe at once).
        let key = (4.0f64.to_bits(), FilmSupply::None);
        let tables: Vec<usize> = std::thread::scope(|s| {
            let handles: Vec<_> = (0..3).map(|_| s.spawn(|| table_for(4.0, FilmSupply::None) as *const _ as usize)).collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        assert!(tables.iter().all(|&t| t == tables[0]), "different tables: {tables:?}");
        let fetched = FETCHED.lock().unwrap().iter().filter(|&&k| k == key).count();
        assert_eq!(fetched, 1, "solved (or read from disk) {fetched} times");
    }

    #[test]
    fn an_unwritable_directory_is_no_cache() {
        // A regular file where the directory should be: creating it fails, the table is still built.
        let base = temp_dir("unwritable");
        std::fs::create_dir_all(&base).unwrap();
        let blocker = base.join("file");
        std::fs::write(&blocker, b"x").unwrap();
        let (t, how) = load_or_build(Some(&blocker.join("sub")), 3.0, FilmSupply::None, GRID);
        assert_eq!(how, TableSource::Built);
        assert_eq!(t, FiniteBearingTable::build(3.0, FilmSupply::None, GRID));
        assert_eq!(load_or_build(None, 3.0, FilmSupply::None, GRID).1, TableSource::Built);
        let _ = std::fs::remove_dir_all(&base);
    }
}
