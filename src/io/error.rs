//! The error every reader returns for a file it cannot read.

use crate::base::error::Error;
use crate::base::limits::escape_controls;

/// `Error::Format` for the file `label` (already fit to print) with
/// `message`, whose control characters are escaped.
pub(crate) fn format_error(label: &str, message: impl Into<String>) -> Error {
    Error::Format { path: label.to_string(), message: escape_controls(&message.into()) }
}
