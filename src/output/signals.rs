//! The signals that end a process, for the two places that answer them: the headless
//! commands (which remove their temporary files first, [`super::sink`]) and the
//! terminal application (which restores the terminal first, `tui::terminal`).

/// Signals whose default action ends the process, other than SIGTERM, SIGHUP and
/// SIGINT (answered on their own), the program's own faults (SIGSEGV, SIGBUS, SIGILL,
/// SIGFPE, SIGTRAP keep their default handling) and SIGPIPE (ignored by the Rust
/// runtime: a closed pipe is a write error).
pub const ENDING: [libc::c_int; 13] = [
    libc::SIGQUIT,
    libc::SIGABRT,
    libc::SIGUSR1,
    libc::SIGUSR2,
    libc::SIGALRM,
    libc::SIGVTALRM,
    libc::SIGPROF,
    libc::SIGIO,
    libc::SIGPWR,
    libc::SIGSTKFLT,
    libc::SIGXCPU,
    libc::SIGXFSZ,
    libc::SIGSYS,
];

/// [`ENDING`] and the real-time signals (whose default action ends the process too).
pub fn ending() -> Vec<libc::c_int> {
    let mut v = ENDING.to_vec();
    v.extend(libc::SIGRTMIN()..=libc::SIGRTMAX());
    v
}

/// End the process by `sig`'s default action (as the shell expects: status 128 + its
/// number, a core where SIGQUIT or SIGABRT leave one): the default disposition back,
/// the signal unblocked, raised again. Async-signal-safe, so a handler may call it.
pub fn die_by(sig: libc::c_int) {
    // SAFETY: sigaction, pthread_sigmask and raise are async-signal-safe; the structures
    // are our own.
    unsafe {
        let mut action: libc::sigaction = std::mem::zeroed();
        action.sa_sigaction = libc::SIG_DFL;
        libc::sigaction(sig, &action, std::ptr::null_mut());
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        libc::sigaddset(&mut set, sig);
        libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
        libc::raise(sig);
    }
}
