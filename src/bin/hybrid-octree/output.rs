//! Printing a report: one JSON object on stdout, or the command's text form.

use hybrid_octree::{Error, Result};
use serde::Serialize;

/// Prints `report` as one JSON object when `json`, else with `text`.
pub fn print_report<T: Serialize>(report: &T, json: bool, text: impl Fn(&T)) -> Result<()> {
    if json {
        let line = serde_json::to_string(report).map_err(|e| Error::Internal(format!("JSON output: {e}")))?;
        println!("{line}");
    } else {
        text(report);
    }
    Ok(())
}
