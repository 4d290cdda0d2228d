//! The belt's initial path around the pulleys.

use crate::error::{BeltError, BeltResult};
use crate::geometry::BeltPath;
use crate::scene::Scene;

/// The path around the scene's pulleys, with its spans clear of the other pulleys and a
/// finite, positive length.
pub(super) fn compile(scene: &Scene) -> BeltResult<BeltPath> {
    let path = BeltPath::from_pulleys(&scene.pulleys)?;
    path.check_spans_clear(&scene.pulleys)?;
    if !(path.length.is_finite() && path.length > 0.0) {
        return Err(BeltError::invalid(
            "pulleys",
            format!("a belt path of {} m", path.length),
            "the path length must be finite and > 0 (centres or radii too large)",
        ));
    }
    Ok(path)
}
