//! # qemu-icount — exact guest instruction counts between two marker functions
//!
//! A QEMU TCG plugin (plugin API v1, which Debian's QEMU 7.2 loads) for benchmarks that run
//! under `qemu-system-*`. The guest calls a *start* marker function right before the code to
//! measure and a *stop* marker function right after it; this plugin reports how many guest
//! instructions executed in between, exactly and deterministically (no timers, no sampling).
//!
//! ```text
//! qemu-system-arm -M mps2-an386 -nographic -semihosting-config enable=on,target=native \
//!     -plugin tools/qemu-icount/target/release/libqemu_icount.so,start=0x4b1,stop=0x4c1,out=counts.txt \
//!     -kernel bench.elf
//! ```
//!
//! Arguments (`key=value`, after the plugin path):
//!
//! - `start=ADDR`, `stop=ADDR` (required): the addresses of the two markers' first
//!   instructions, hex with `0x` or decimal. Bit 0 is ignored, so Thumb symbol values from
//!   `readelf -s` / `nm` can be passed as they are.
//! - `out=PATH` (optional): also write one line per pair to this file.
//!
//! **What is counted.** Every guest instruction gets an inline `ADD_U64 1` on a counter (the
//! add is emitted into the translated code before the instruction, so it counts instructions
//! that started executing; a block left early by an exception counts only what ran). The first
//! instruction of each marker also gets an exec callback that reads the counter. A *pair* is a
//! start hit followed by a stop hit; its count is every instruction executed from the start
//! marker's first instruction (inclusive) up to the stop marker's first instruction
//! (exclusive): the start marker's body and return, the measured code, and the call into the
//! stop marker. Both callbacks sit in the same place relative to their instruction's add, so
//! the difference is exact whichever order QEMU emits them in. A condition-failed instruction
//! (IT block) counts, as architecturally it executes. Instruction counts are not cycles.
//!
//! **Output.** Each completed pair prints, in order, to QEMU's stderr (and to `out=`):
//!
//! ```text
//! qemu-icount: pair=1 instructions=1234567
//! ```
//!
//! A start while a pair is open restarts it, a stop without a start is ignored; both are
//! reported on stderr, and the exit summary (`qemu-icount: 3 pairs`) says how many were
//! counted. Pairs are numbered from 1 in the order they complete.
//!
//! The counter is not atomic, so the plugin refuses to load on a machine with more than one
//! vCPU (the Cortex-M boards have one).
#![allow(non_upper_case_globals)] // `qemu_plugin_version` is the name QEMU looks up.

use qemu_plugin_sys::{
    qemu_info_t, qemu_plugin_cb_flags, qemu_plugin_id_t, qemu_plugin_insn_vaddr, qemu_plugin_op,
    qemu_plugin_register_atexit_cb, qemu_plugin_register_vcpu_insn_exec_cb,
    qemu_plugin_register_vcpu_insn_exec_inline, qemu_plugin_register_vcpu_tb_trans_cb,
    qemu_plugin_tb, qemu_plugin_tb_get_insn, qemu_plugin_tb_n_insns, QEMU_PLUGIN_VERSION,
};
use std::ffi::{c_char, c_int, c_uint, c_void, CStr};
use std::fs::File;
use std::io::Write as _;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

/// The plugin API version this plugin was built against; QEMU refuses a mismatch.
#[no_mangle]
pub static qemu_plugin_version: c_int = QEMU_PLUGIN_VERSION as c_int;

/// Guest instructions executed since the plugin was loaded. The translated code adds 1 before
/// every instruction (plain, non-atomic stores from the single vCPU thread).
static EXECUTED: AtomicU64 = AtomicU64::new(0);

/// What the plugin was told and what it has counted.
struct State {
    /// Address of the start marker's first instruction (bit 0 cleared).
    start: u64,
    /// Address of the stop marker's first instruction (bit 0 cleared).
    stop: u64,
    /// `EXECUTED` at the open pair's start, if a pair is open.
    open: Option<u64>,
    /// Completed pairs.
    pairs: u64,
    /// Optional copy of the output.
    out: Option<File>,
}

static STATE: Mutex<Option<State>> = Mutex::new(None);

/// Runs `f` on the state (present once `qemu_plugin_install` succeeded).
fn with_state(f: impl FnOnce(&mut State)) {
    let mut guard = STATE.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(state) = guard.as_mut() {
        f(state);
    }
}

/// Parses `0x`-prefixed hex or decimal.
fn parse_addr(value: &str) -> Option<u64> {
    match value
        .strip_prefix("0x")
        .or_else(|| value.strip_prefix("0X"))
    {
        Some(hex) => u64::from_str_radix(hex, 16).ok(),
        None => value.parse().ok(),
    }
}

/// Reads the plugin's `key=value` arguments.
fn parse_args(args: &[String]) -> Result<State, String> {
    let (mut start, mut stop, mut out) = (None, None, None);
    for arg in args {
        let (key, value) = arg
            .split_once('=')
            .ok_or_else(|| format!("argument `{arg}` is not key=value"))?;
        let addr = || parse_addr(value).ok_or_else(|| format!("`{arg}`: not an address"));
        match key {
            "start" => start = Some(addr()? & !1),
            "stop" => stop = Some(addr()? & !1),
            "out" => {
                let file = File::create(value).map_err(|e| format!("`{arg}`: {e}"))?;
                out = Some(file);
            }
            _ => {
                return Err(format!(
                    "unknown argument `{arg}` (expected start=, stop=, out=)"
                ))
            }
        }
    }
    let start = start.ok_or("missing start=ADDR (the start marker's address)")?;
    let stop = stop.ok_or("missing stop=ADDR (the stop marker's address)")?;
    if start == stop {
        return Err(format!(
            "start and stop are both {start:#x}: the markers were merged; give them different bodies"
        ));
    }
    Ok(State {
        start,
        stop,
        open: None,
        pairs: 0,
        out,
    })
}

/// Exec callback on the start marker's first instruction: opens a pair.
unsafe extern "C" fn on_start(_vcpu: c_uint, _udata: *mut c_void) {
    let now = EXECUTED.load(Ordering::Relaxed);
    with_state(|s| {
        if s.open.is_some() {
            eprintln!("qemu-icount: start hit again before stop; restarting the pair");
        }
        s.open = Some(now);
    });
}

/// Exec callback on the stop marker's first instruction: closes the open pair and reports it.
unsafe extern "C" fn on_stop(_vcpu: c_uint, _udata: *mut c_void) {
    let now = EXECUTED.load(Ordering::Relaxed);
    with_state(|s| {
        let Some(begin) = s.open.take() else {
            eprintln!("qemu-icount: stop hit without a start; ignored");
            return;
        };
        s.pairs += 1;
        let line = format!(
            "qemu-icount: pair={} instructions={}",
            s.pairs,
            now.wrapping_sub(begin)
        );
        eprintln!("{line}");
        if let Some(out) = s.out.as_mut() {
            if let Err(e) = writeln!(out, "{line}").and_then(|_| out.flush()) {
                eprintln!("qemu-icount: cannot write the out= file: {e}");
            }
        }
    });
}

/// Translation callback: instruments every instruction of a new translation block.
unsafe extern "C" fn on_translate(_id: qemu_plugin_id_t, tb: *mut qemu_plugin_tb) {
    let (mut start, mut stop) = (u64::MAX, u64::MAX);
    with_state(|s| (start, stop) = (s.start, s.stop));
    // SAFETY: `tb` is valid for the duration of this callback, and so is every instruction
    // handle taken from it; `EXECUTED` is a static, so the inline add's target outlives QEMU's
    // use of it.
    unsafe {
        for i in 0..qemu_plugin_tb_n_insns(tb) {
            let insn = qemu_plugin_tb_get_insn(tb, i);
            let vaddr = qemu_plugin_insn_vaddr(insn);
            let marker = if vaddr == start {
                Some(on_start as unsafe extern "C" fn(c_uint, *mut c_void))
            } else if vaddr == stop {
                Some(on_stop as unsafe extern "C" fn(c_uint, *mut c_void))
            } else {
                None
            };
            if let Some(cb) = marker {
                qemu_plugin_register_vcpu_insn_exec_cb(
                    insn,
                    Some(cb),
                    qemu_plugin_cb_flags::QEMU_PLUGIN_CB_NO_REGS,
                    std::ptr::null_mut(),
                );
            }
            qemu_plugin_register_vcpu_insn_exec_inline(
                insn,
                qemu_plugin_op::QEMU_PLUGIN_INLINE_ADD_U64,
                EXECUTED.as_ptr().cast(),
                1,
            );
        }
    }
}

/// At QEMU's exit: the summary line, and a warning for a pair left open.
unsafe extern "C" fn on_exit(_id: qemu_plugin_id_t, _udata: *mut c_void) {
    with_state(|s| {
        if s.open.is_some() {
            eprintln!("qemu-icount: a pair was still open at exit (start without stop)");
        }
        eprintln!("qemu-icount: {} pairs", s.pairs);
    });
}

/// Entry point QEMU calls when it loads the plugin.
///
/// # Safety
///
/// Called by QEMU only: `info` valid, `argv` holding `argc` NUL-terminated strings.
#[no_mangle]
pub unsafe extern "C" fn qemu_plugin_install(
    id: qemu_plugin_id_t,
    info: *const qemu_info_t,
    argc: c_int,
    argv: *mut *mut c_char,
) -> c_int {
    // SAFETY: QEMU passes `argc` valid C strings in `argv` and a valid `info`.
    let (args, vcpus) = unsafe {
        let args: Vec<String> = (0..argc.max(0) as usize)
            .map(|i| CStr::from_ptr(*argv.add(i)).to_string_lossy().into_owned())
            .collect();
        let vcpus = if (*info).system_emulation {
            (*info).__bindgen_anon_1.system.max_vcpus
        } else {
            1
        };
        (args, vcpus)
    };
    if vcpus > 1 {
        eprintln!("qemu-icount: {vcpus} vCPUs; the counter is exact for one vCPU only");
        return -1;
    }
    match parse_args(&args) {
        Ok(state) => {
            *STATE.lock().unwrap_or_else(|e| e.into_inner()) = Some(state);
        }
        Err(e) => {
            eprintln!("qemu-icount: {e}");
            return -1;
        }
    }
    // SAFETY: registering callbacks with the id QEMU gave us, from the install hook.
    unsafe {
        qemu_plugin_register_vcpu_tb_trans_cb(id, Some(on_translate));
        qemu_plugin_register_atexit_cb(id, Some(on_exit), std::ptr::null_mut());
    }
    0
}
