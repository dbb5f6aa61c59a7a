//! AVSM against the transmittance truth where the receivers lie inside the medium (the
//! `ramp` scene): there each receiver reads the curve at its own depth, so the compression
//! to fewer nodes shows, and the error falls as the nodes grow.

use crate::common;

use shadowmap::compare::compare;
use shadowmap::reference::TransmittanceMetrics;
use shadowmap::settings::{ShadowSettings, Volumetric};
use shadowmap::Scene;

/// AVSM with `nodes` nodes a texel on the ramp at 320x180, scored against the truth.
fn avsm(scene: &Scene, nodes: u32) -> TransmittanceMetrics {
    let settings = ShadowSettings {
        volumetric: Volumetric::Avsm,
        avsm_nodes: nodes,
        ..scene.shadow
    };
    let ctx = common::context();
    let opts = common::frame_options(scene.size[0], scene.size[1]);
    let c = compare(ctx.gl(), scene, &settings, &opts).unwrap_or_else(|e| panic!("{e}"));
    let t = c.transmittance.expect("the ramp has translucent casters");
    eprintln!("avsm, {nodes} nodes: {t:?}");
    t
}

#[test]
fn inside_the_medium_avsm_s_error_falls_as_its_nodes_grow() {
    let scene = Scene {
        size: [320, 180],
        ..common::frozen("ramp")
    };
    let [two, four, eight] = [2, 4, 8].map(|n| avsm(&scene, n).mae_in_shadow);
    eprintln!("ramp, AVSM MAE in the translucent shadow: 2 {two:.4}, 4 {four:.4}, 8 {eight:.4}");
    // Measured: 0.0440, 0.0343, 0.0327 (the rest is the map's resolution at the puffs'
    // rims, which no node count changes).
    assert!(
        two > 1.2 * four && four > 1.03 * eight,
        "{two} {four} {eight}"
    );
    for (nodes, mae, measured) in [(2, two, 0.0440), (4, four, 0.0343), (8, eight, 0.0327)] {
        assert!(
            (mae - measured).abs() < 0.05 * measured,
            "{nodes} nodes: {mae}, measured {measured}"
        );
    }
}
