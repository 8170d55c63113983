//! Where finite-bearing tables are kept between uses (docs/physics.md §4, finite bearing): a
//! process cache keyed by (D/L, supply convention) over a disk cache in the user's cache
//! directory, so that only the first process on a machine ever solves a table.
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
use std::sync::{Mutex, OnceLock};

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

/// The table of a bearing with diameter-to-length ratio `k` and supply convention `supply` on the
/// default grid: from this process's cache, else from the disk cache, else solved (a few seconds
/// on two cores) and stored in both. Kept for the life of the process.
pub fn table_for(k: f64, supply: FilmSupply) -> &'static FiniteBearingTable {
    type Key = (u64, FilmSupply);
    static CACHE: OnceLock<Mutex<HashMap<Key, &'static FiniteBearingTable>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    let key = (k.to_bits(), supply);
    if let Some(t) = cache.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
        return t;
    }
    // Not holding the lock while solving: two threads asking for one new table may both solve it
    // (the first one stored wins), but no thread ever waits on another's parallel solve.
    let (table, _) = load_or_build(cache_dir().as_deref(), k, supply, ReynoldsGrid::default());
    let table: &'static FiniteBearingTable = Box::leak(Box::new(table));
    cache.lock().unwrap_or_else(|e| e.into_inner()).entry(key).or_insert(table)
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
