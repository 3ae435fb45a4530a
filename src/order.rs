//! Compositing order: bricks back to front (and front to back) for a camera.
