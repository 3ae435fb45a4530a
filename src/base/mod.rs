//! What every layer uses: the crate's one error type ([`error`]) and the
//! limits checked before a request is attempted ([`limits`]: the memory a
//! buffer would take, excerpts of user text fit to print in a message).

pub mod error;
pub mod limits;
