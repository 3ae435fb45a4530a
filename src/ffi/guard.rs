//! No panic crosses the bridge: every bridge function's body runs in [`guarded`].

use crate::error::Error;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// What a bridge function returns: an error crosses as its message.
pub(crate) type Bridged<T> = std::result::Result<T, String>;

/// Runs `f`, turning a panic into [`Error::Internal`] so it never crosses the bridge.
pub(crate) fn guarded<T>(f: impl FnOnce() -> crate::error::Result<T>) -> Bridged<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(value)) => Ok(value),
        Ok(Err(e)) => Err(e.to_string()),
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".to_string());
            Err(Error::Internal(what).to_string())
        }
    }
}

/// Checks that the caller's buffer `name` holds `expected` values.
pub(crate) fn check_len<T>(name: &str, buffer: &[T], expected: usize) -> crate::error::Result<()> {
    if buffer.len() == expected {
        Ok(())
    } else {
        Err(Error::InvalidArgument(format!("the buffer for {name} holds {} values, {expected} expected", buffer.len())))
    }
}

/// Copies a picture's premultiplied RGBA `pixels` into the caller's
/// `rgba` (4 floats a pixel), after checking that it holds them all.
pub(crate) fn write_pixels(pixels: &[[f32; 4]], rgba: &mut [f32]) -> crate::error::Result<()> {
    check_len("the picture", rgba, 4 * pixels.len())?;
    for (pixel, to) in pixels.iter().zip(rgba.chunks_exact_mut(4)) {
        to.copy_from_slice(pixel);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_an_error_not_an_abort() {
        let r: Bridged<()> = guarded(|| panic!("boom"));
        let e = r.unwrap_err();
        assert!(e.contains("internal error") && e.contains("boom"), "{e}");
    }

    #[test]
    fn a_buffer_of_the_wrong_size_is_named() {
        let e = check_len("texels", &[0.0f32; 3], 4).unwrap_err().to_string();
        assert!(e.contains("texels") && e.contains("3 values, 4 expected"), "{e}");
    }
}
