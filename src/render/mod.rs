//! The CPU compositor (executes a DrawList), the full-resolution reference
//! ray caster, transfer functions and image metrics.
