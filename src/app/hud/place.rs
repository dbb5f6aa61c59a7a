//! Where the HUD's panels go: the corner of the frame whose panels cover none of what the
//! scene shows, its casters' silhouettes from the scene's camera. A panel's dark ground dims
//! what is under it, so a cube under the text hides the lesson the step is about.

use glam::DVec3;
use shadowmap::Scene;

use super::MARGIN;

/// A corner of the frame the panels can take (the bottom-right one holds the inset).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Corner {
    TopLeft,
    TopRight,
    BottomLeft,
}

impl Corner {
    /// The corners in the order they are tried: the book's top-left first.
    const ALL: [Corner; 3] = [Corner::TopLeft, Corner::TopRight, Corner::BottomLeft];

    /// The top-left point of a `column` (width, height) of panels in this corner of a
    /// `size` frame.
    pub(super) fn origin(self, size: (u32, u32), column: (f32, f32)) -> (f32, f32) {
        let right = (size.0 as f32 - MARGIN - column.0).floor();
        let bottom = (size.1 as f32 - MARGIN - column.1).floor();
        match self {
            Corner::TopLeft => (MARGIN, MARGIN),
            Corner::TopRight => (right, MARGIN),
            Corner::BottomLeft => (MARGIN, bottom),
        }
    }

    /// Whether the panels hug the frame's right edge.
    pub(super) fn right(self) -> bool {
        match self {
            Corner::TopLeft | Corner::BottomLeft => false,
            Corner::TopRight => true,
        }
    }
}

/// The corner for a `column` of panels: the first (top-left, top-right, bottom-left) that
/// covers no item's silhouette; else the first that covers no translucent item (what a
/// scene with them is about); else the top-left. A corner must leave the frame room for the
/// column, and the bottom-left room for the inset beside it.
pub(super) fn corner(scene: &Scene, size: (u32, u32), column: (f32, f32)) -> Corner {
    let shapes = silhouettes(scene, size);
    let fits = |c: Corner| {
        let (x, y) = c.origin(size, column);
        let inset = (size.1 / 4) as f32 + 2.0 * MARGIN;
        let room = match c {
            Corner::BottomLeft => x + column.0 <= size.0 as f32 - inset,
            Corner::TopLeft | Corner::TopRight => true,
        };
        room && x >= MARGIN && y >= MARGIN
    };
    let covers = |c: Corner, translucent_only: bool| {
        let (x, y) = c.origin(size, column);
        let rect = [x, y, x + column.0, y + column.1];
        shapes
            .iter()
            .filter(|(translucent, _)| *translucent || !translucent_only)
            .any(|(_, hull)| overlaps(hull, rect))
    };
    let candidates = || Corner::ALL.into_iter().filter(|&c| fits(c));
    candidates()
        .find(|&c| !covers(c, false))
        .or_else(|| candidates().find(|&c| !covers(c, true)))
        .unwrap_or(Corner::TopLeft)
}

/// Each item that stands out of the scene (a mesh with depth: a floor is flat, and is
/// under every panel) as it falls on a `size` frame from the scene's camera: the convex
/// hull of its mesh box's corners in front of the camera (pixels from the top-left, y
/// down), and whether it is translucent.
pub(super) fn silhouettes(scene: &Scene, size: (u32, u32)) -> Vec<(bool, Vec<[f32; 2]>)> {
    let to_clip = shadowmap::motion::view_projection(&scene.camera, size.0, size.1);
    let (w, h) = (f64::from(size.0), f64::from(size.1));
    // Each mesh's bounds once, for the items that share it (the smoke's puffs).
    let mut bounds = vec![None; scene.meshes.len()];
    let mut shapes = Vec::new();
    for item in &scene.items {
        let (lo, hi) = *bounds[item.mesh].get_or_insert_with(|| scene.meshes[item.mesh].bounds());
        let extent = hi - lo;
        let flat = extent.min_element() <= 1e-4 * extent.max_element();
        if flat && !item.is_translucent() {
            continue;
        }
        let model = item.model_matrix64();
        let mut points = Vec::new();
        for corner in 0..8 {
            let pick =
                |bit: usize, l: f32, h: f32| f64::from(if corner & bit == 0 { l } else { h });
            let local = DVec3::new(
                pick(1, lo.x, hi.x),
                pick(2, lo.y, hi.y),
                pick(4, lo.z, hi.z),
            );
            let clip = to_clip * model.transform_point3(local).extend(1.0);
            if clip.w <= 1e-9 {
                continue;
            }
            let px = ((clip.x / clip.w * 0.5 + 0.5) * w) as f32;
            let py = ((0.5 - clip.y / clip.w * 0.5) * h) as f32;
            points.push([px, py]);
        }
        if !points.is_empty() {
            shapes.push((item.is_translucent(), hull(points)));
        }
    }
    shapes
}

/// The convex hull of `points` (Andrew's monotone chain), counter-clockwise in y-down
/// pixels; a single point or a segment as it is.
fn hull(mut points: Vec<[f32; 2]>) -> Vec<[f32; 2]> {
    points.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let cross = |o: [f32; 2], a: [f32; 2], b: [f32; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut out: Vec<[f32; 2]> = Vec::new();
    for pass in [points.clone(), points.into_iter().rev().collect()] {
        let start = out.len();
        for p in pass {
            while out.len() >= start + 2 && cross(out[out.len() - 2], out[out.len() - 1], p) <= 0.0
            {
                out.pop();
            }
            out.push(p);
        }
        out.pop();
    }
    out
}

/// Whether the convex polygon `hull` and the rectangle `[x0, y0, x1, y1]` share any area:
/// no separating axis among the rectangle's two and the polygon's edge normals.
pub(super) fn overlaps(hull: &[[f32; 2]], rect: [f32; 4]) -> bool {
    let [x0, y0, x1, y1] = rect;
    let corners = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
    let span = |points: &mut dyn Iterator<Item = [f32; 2]>, axis: [f32; 2]| {
        points
            .map(|p| p[0] * axis[0] + p[1] * axis[1])
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), d| {
                (lo.min(d), hi.max(d))
            })
    };
    let mut axes = vec![[1.0, 0.0], [0.0, 1.0]];
    for (i, a) in hull.iter().enumerate() {
        let b = hull[(i + 1) % hull.len()];
        axes.push([a[1] - b[1], b[0] - a[0]]);
    }
    axes.into_iter().all(|axis| {
        let (a_lo, a_hi) = span(&mut hull.iter().copied(), axis);
        let (b_lo, b_hi) = span(&mut corners.iter().copied(), axis);
        a_lo < b_hi && b_lo < a_hi
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_beside_a_rectangle_overlaps_it_only_across_its_diagonal() {
        // The triangle (0, 0), (10, 0), (0, 10): its hypotenuse is x + y = 10.
        let tri = hull(vec![[0.0, 0.0], [10.0, 0.0], [0.0, 10.0], [2.0, 2.0]]);
        assert_eq!(tri.len(), 3, "{tri:?}");
        assert!(overlaps(&tri, [4.0, 4.0, 9.0, 9.0]));
        // The box's corner nearest the triangle is (6, 6): beyond the hypotenuse, though
        // the triangle's bounding box holds it.
        assert!(!overlaps(&tri, [6.0, 6.0, 9.0, 9.0]));
        assert!(!overlaps(&tri, [11.0, 0.0, 12.0, 1.0]));
    }
}
