//! How `casadi_peer` times a call: alone (the loop of the C harness, run as
//! a program of its own, which `run.sh` alternates with ours), or beside
//! the C's function in this process, batch for batch
//! (`--interleave libharness.so`), which gives a ratio from batches a few
//! milliseconds apart: on a shared virtual machine whose speed drifts by
//! tens of percent within seconds, the programs' alternation does not.

use std::ffi::{CString, c_char, c_int, c_long, c_void};
use std::hint::black_box;
use std::time::Instant;

/// Batches per measurement (the medians are reported).
const BATCHES: usize = 31;

/// The C harness as a library (`peer/casadi/harness.c` built with
/// `CASADI_PEER_LIBRARY`, by `casadi_codegen.py`).
pub struct Peer {
    open: unsafe extern "C" fn(*const c_char, *const c_char, c_int) -> *mut c_void,
    run: unsafe extern "C" fn(*mut c_void, c_long) -> f64,
    close: unsafe extern "C" fn(*mut c_void),
    // Kept open for the three functions above.
    _library: libloading::Library,
}

impl Peer {
    /// The library at `path`, or why not.
    pub fn load(path: &str) -> Result<Peer, String> {
        // SAFETY: libharness.so is the C harness built by casadi_codegen.py;
        // loading it runs no initialiser of its own, and the three symbols
        // have the signatures of harness.c's peer_open, peer_run and
        // peer_close, whose pointers are copied out while the library stays
        // open in `_library`.
        unsafe {
            let library = libloading::Library::new(path).map_err(|e| format!("{path}: {e}"))?;
            let open = *library
                .get(b"peer_open\0")
                .map_err(|e| format!("{path}: {e}"))?;
            let run = *library
                .get(b"peer_run\0")
                .map_err(|e| format!("{path}: {e}"))?;
            let close = *library
                .get(b"peer_close\0")
                .map_err(|e| format!("{path}: {e}"))?;
            Ok(Peer {
                open,
                run,
                close,
                _library: library,
            })
        }
    }
}

/// How each of our quantities is timed, and with which of the C's
/// functions it is paired.
pub struct Timer<'a> {
    pub robot: &'a str,
    pub wide: bool,
    pub peer: Option<&'a Peer>,
}

impl Timer<'_> {
    /// Times `f` as `quantity` and prints its `time` line; interleaved, also
    /// a `pair` line: the C's and our medians over the batches, and the
    /// median of the batches' ratios (C / ours).
    pub fn time<R>(&self, quantity: &str, f: impl FnMut() -> R) {
        let c_name = quantity
            .trim_end_matches("_terms")
            .trim_end_matches("_runtime");
        let bound = self
            .peer
            .and_then(|peer| Bound::new(peer, self.robot, c_name, self.wide));
        let Some(c) = bound else {
            let t = median(alone(f));
            println!("time {} {quantity} {t:.1}", self.robot);
            return;
        };
        let (ours, theirs) = interleaved(f, &c);
        let ratios: Vec<f64> = theirs.iter().zip(&ours).map(|(c, o)| c / o).collect();
        let (o, c, r) = (median(ours), median(theirs), median(ratios));
        println!("time {} {quantity} {o:.1}", self.robot);
        println!("pair {} {quantity} {c:.1} {o:.1} {r:.3}", self.robot);
    }
}

/// One of the C's functions at its state (`peer_open`), closed on drop.
struct Bound<'a> {
    peer: &'a Peer,
    handle: *mut c_void,
}

impl<'a> Bound<'a> {
    fn new(peer: &'a Peer, robot: &str, quantity: &str, wide: bool) -> Option<Bound<'a>> {
        let (robot, quantity) = (CString::new(robot).ok()?, CString::new(quantity).ok()?);
        // SAFETY: two NUL-terminated strings that outlive the call; NULL
        // (no such function) is checked.
        let handle = unsafe { (peer.open)(robot.as_ptr(), quantity.as_ptr(), c_int::from(wide)) };
        (!handle.is_null()).then_some(Bound { peer, handle })
    }

    /// ns per call over a batch of `calls`.
    fn batch(&self, calls: usize) -> f64 {
        // SAFETY: a live handle from peer_open.
        let seconds = unsafe { (self.peer.run)(self.handle, calls as c_long) };
        seconds * 1e9 / calls as f64
    }
}

impl Drop for Bound<'_> {
    fn drop(&mut self) {
        // SAFETY: a live handle from peer_open, closed once.
        unsafe { (self.peer.close)(self.handle) }
    }
}

/// ns per call of `f` over a batch of `calls`. Each result is left where
/// the call wrote it and only its address is hidden from the optimiser, as
/// the C's outputs stay in the buffers it writes: `black_box(f())` would
/// move it first, and a copy of a matrix that was just stored entry by
/// entry, read back a register at a time, waits for those stores to reach
/// the cache (the UR5's M + (Q − h): 105 against 61 ns).
fn batch<R>(f: &mut impl FnMut() -> R, calls: usize) -> f64 {
    let start = Instant::now();
    for _ in 0..calls {
        let result = f();
        black_box(&result);
    }
    start.elapsed().as_secs_f64() * 1e9 / calls as f64
}

/// The number of calls that lasts about 2 ms (the sizing runs warm up).
fn calls_for(mut ns_per_call: impl FnMut(usize) -> f64) -> usize {
    let mut calls = 1usize;
    while ns_per_call(calls) * (calls as f64) < 2e6 {
        calls *= 2;
    }
    calls
}

/// [`BATCHES`] batches of `f`, as the C harness times its functions.
fn alone<R>(mut f: impl FnMut() -> R) -> Vec<f64> {
    let calls = calls_for(|n| batch(&mut f, n));
    (0..BATCHES).map(|_| batch(&mut f, calls)).collect()
}

/// [`BATCHES`] batches of `f` and as many of the C's function, alternated.
fn interleaved<R>(mut f: impl FnMut() -> R, c: &Bound) -> (Vec<f64>, Vec<f64>) {
    let ours_calls = calls_for(|n| batch(&mut f, n));
    let c_calls = calls_for(|n| c.batch(n));
    (0..BATCHES)
        .map(|_| (batch(&mut f, ours_calls), c.batch(c_calls)))
        .unzip()
}

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}
