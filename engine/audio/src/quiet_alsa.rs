//! ALSA's library writes its complaints (no sound card, no `default` device) straight to
//! stderr, eight lines of them on a machine without sound. While the device opens they are
//! caught on this thread instead (ALSA's thread-local error handler) and logged at debug level,
//! so such a machine says it has no sound in one line.

/// Runs `open` with ALSA's messages on this thread caught and logged at debug level.
#[cfg(target_os = "linux")]
pub fn while_opening<T>(open: impl FnOnce() -> T) -> T {
    let caught = alsa::Output::local_error_handler();
    let result = open();
    if let Ok(buffer) = caught {
        let text = buffer.borrow().to_string();
        if !text.trim().is_empty() {
            log::debug!("sound: ALSA: {}", text.trim().replace('\n', "; "));
        }
    }
    result
}

#[cfg(not(target_os = "linux"))]
pub fn while_opening<T>(open: impl FnOnce() -> T) -> T {
    open()
}
