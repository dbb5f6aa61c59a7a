//! The tutorials' steps as data: each step is a named preset of [`ShadowSettings`], built by
//! applying every earlier step's change to the tutorial's starting point. Nothing here
//! draws; the renderer is the same for every step. A scene names its list (`[steps] list`):
//! the chapters' ([`STEPS`]) or the shadow-playground's demo pages ([`PLAYGROUND_STEPS`]).

use crate::error::{Error, Result};
use crate::scene::{Scene, StepContext, StepList};
use crate::settings::{
    BeyondFar, BiasMode, Blur, Cull, Filter, LightProjection, MapSize, MsmToward, PerspectiveDepth,
    ShadowSettings, ShadowTechnique, Wrap,
};

/// One step of the chapters.
pub struct Step {
    pub name: &'static str,
    /// What changed from the previous step.
    pub change: &'static str,
    /// What to look for in the picture.
    pub look_for: &'static str,
    /// Whether the step carries over into the following ones (variants do not).
    pub cumulative: bool,
    apply: fn(&mut ShadowSettings, &StepContext),
}

/// The steps in the chapters' order (LWJGL "Shadows", LearnOpenGL "Shadow Mapping", the
/// slides' larger maps and perspective light, and the slides' closing shadow volumes).
pub const STEPS: &[Step] = &[
    Step {
        name: "depth-map",
        change: "The first pass only: the scene as the light sees it, stored as depth.",
        look_for: "Dark is near the light. An orthographic map is shown raw; a perspective one \
                   is linearised first.",
        cumulative: false,
        apply: |s, _| s.show_depth_map = true,
    },
    Step {
        name: "no-bias",
        change: "The plain comparison: a fragment is in shadow when it is farther from the \
                 light than the depth stored for its texel.",
        look_for: "Shadow acne: stripes of false shadow on every lit surface.",
        cumulative: true,
        apply: |s, _| s.bias_mode = BiasMode::None,
    },
    Step {
        name: "bias",
        change: "A constant bias is subtracted from the fragment's depth (the book 0.05, \
                 LearnOpenGL 0.005).",
        look_for: "The acne is gone; a large bias detaches shadows from their casters.",
        cumulative: true,
        apply: |s, c| {
            s.bias_mode = BiasMode::Constant;
            s.bias = c.bias;
        },
    },
    Step {
        name: "slope-bias",
        change: "LearnOpenGL's slope-scaled bias: max(0.05 (1 - n.l), 0.005).",
        look_for: "Surfaces facing the light get a small bias, grazing ones a larger one.",
        cumulative: true,
        apply: |s, _| {
            s.bias_mode = BiasMode::Slope;
            s.bias = 0.05;
            s.bias_min = 0.005;
        },
    },
    Step {
        name: "cull-front",
        change: "Front faces are culled in the depth pass, so closed objects store their back \
                 faces.",
        look_for: "Less peter panning at contacts; single-sided geometry still casts only if \
                   wound to face away from the light.",
        cumulative: true,
        apply: |s, _| s.cull = Cull::Front,
    },
    Step {
        name: "over-sampling-repeat",
        change: "The shadow map wraps with REPEAT (LearnOpenGL's first steps).",
        look_for: "False shadows outside the light's box: the map repeats across the floor.",
        cumulative: false,
        apply: |s, _| {
            s.wrap = Wrap::Repeat;
            s.beyond_far = BeyondFar::Shadowed;
        },
    },
    Step {
        name: "over-sampling-book",
        change: "The book's choice: CLAMP_TO_EDGE and no test past the far plane.",
        look_for: "Outside the box the edge texels repeat; beyond the far plane everything is \
                   shadowed.",
        cumulative: false,
        apply: |s, _| {
            s.wrap = Wrap::ClampToEdge;
            s.beyond_far = BeyondFar::Shadowed;
        },
    },
    Step {
        name: "over-sampling",
        change: "LearnOpenGL's fix: clamp to a border of depth 1 and treat z > 1 as lit.",
        look_for: "Everything outside the light's box is lit.",
        cumulative: true,
        apply: |s, _| {
            s.wrap = Wrap::ClampToBorder;
            s.beyond_far = BeyondFar::Lit;
        },
    },
    Step {
        name: "pcf",
        change: "Percentage-closer filtering: the average of a 3 x 3 block of comparisons.",
        look_for: "Softer, less blocky shadow edges with intermediate values.",
        cumulative: true,
        apply: |s, _| s.filter = Filter::Pcf3x3,
    },
    Step {
        name: "hi-res",
        change: "A 4096 x 4096 shadow map (the slides go 2K, 4K, 8K).",
        look_for: "Sharper edges: each texel covers a sixteenth of the area.",
        cumulative: true,
        apply: |s, _| s.map_size = s.map_size.at_least(4096),
    },
    Step {
        name: "perspective",
        change: "A perspective light projection from the shadow position (the slides and the \
                 blog): a point-like light.",
        look_for: "Shadows spread out with distance from the light.",
        cumulative: false,
        apply: |s, _| {
            s.light_projection = LightProjection::Perspective;
            s.perspective_depth = PerspectiveDepth::Hyperbolic;
        },
    },
    Step {
        name: "perspective-depth-map",
        change: "The perspective light's depth map, linearised for display.",
        look_for: "Without linearising, everything past the nearest surfaces would be white.",
        cumulative: false,
        apply: |s, _| {
            s.light_projection = LightProjection::Perspective;
            s.perspective_depth = PerspectiveDepth::Hyperbolic;
            s.show_depth_map = true;
        },
    },
    Step {
        name: "shadow-volumes",
        change: "The slides' last section: stencil shadow volumes instead of a map. Silhouettes \
                 are extruded away from the light in a geometry shader and the stencil counts \
                 the volume faces behind each pixel (z-fail): exact hard shadows, no texels, no \
                 bias.",
        look_for: "Hard, pixel-exact edges with no acne and no peter panning; the error image \
                   is grey but for single pixels on the edges.",
        cumulative: false,
        apply: |s, _| s.technique = ShadowTechnique::Volumes,
    },
];

/// The shadow-playground's demo pages in its order (basic, PCF, soft PCF; its variance and
/// moment pages are filters of their own), then PCSS, which the engines add.
pub const PLAYGROUND_STEPS: &[Step] = &[
    Step {
        name: "basic",
        change: "The playground's basic demo: one comparison, shadowed when the fragment is \
                 more than its epsilon (5e-3) behind the stored depth.",
        look_for: "Hard, blocky edges; texels of the 400 x 300 map show along them.",
        cumulative: true,
        apply: |s, c| {
            s.filter = Filter::Single;
            s.bias_mode = BiasMode::Constant;
            s.bias = c.bias;
        },
    },
    Step {
        name: "pcf",
        change: "Its PCF demo: 16 taps at +-0.5 and +-1.5 texels, the inner 2 x 2 weighing 0.6 \
                 in all and the outer 12 weighing 0.4; epsilon 1.125e-2; the map twice the \
                 canvas (800 x 600).",
        look_for: "Edges soften over about three texels; the larger epsilon detaches the shadow \
                   a little at the contact.",
        cumulative: true,
        apply: |s, _| {
            s.filter = Filter::Pcf4x4Weighted;
            s.bias = 1.125e-2;
            s.map_size = MapSize {
                width: s.map_size.width * 2,
                height: s.map_size.height * 2,
            };
        },
    },
    Step {
        name: "soft-pcf",
        change: "Its soft PCF demo: the same taps, each comparison through the sigmoid \
                 1 / (1 + exp(-1000 diff)).",
        look_for: "Smoother steps inside the penumbra; surfaces within a few thousandths of \
                   depth of their own texels are slightly darker.",
        cumulative: true,
        apply: |s, _| s.filter = Filter::SoftPcf,
    },
    Step {
        name: "variance",
        change: "Its variance demo: the map stores (z, z^2), blurred by its 3 x 3 Gaussian \
                 (0.045 / 0.122 / 0.332), and Chebyshev's bound gives the lit fraction \
                 (variance at least 1e-8, no bleeding reduction, as the demo).",
        look_for: "Smooth edges from one filtered lookup; where the slab's shadow falls behind \
                   the cube's, light bleeds into it.",
        cumulative: true,
        apply: |s, _| {
            s.filter = Filter::Vsm;
            s.blur = Blur::Playground3x3;
            s.min_variance = 1e-8;
            s.bleed_reduction = 0.0;
        },
    },
    Step {
        name: "moment",
        change: "Its moment demo: (z, z^2, z^3, z^4), the same blur, the moments biased by \
                 9e-4 toward (0, 0.63, 0, 0.63), the Hamburger four-moment reconstruction.",
        look_for: "Edges as soft as the variance step's, with less light bleeding.",
        cumulative: true,
        apply: |s, _| {
            s.filter = Filter::Msm;
            s.msm_bias = 9e-4;
            s.msm_toward = MsmToward::Playground;
        },
    },
    Step {
        name: "pcss",
        change: "Percentage-closer soft shadows (the engines' answer): a blocker search, then a \
                 filter as wide as the penumbra the light's size casts from that depth.",
        look_for: "Shadows sharp where the cube touches the slab and wider away from it, as the \
                   area-light truth's.",
        cumulative: true,
        apply: |s, _| s.filter = Filter::Pcss,
    },
];

/// The steps of `scene`'s list (`[steps] list`).
pub fn of(scene: &Scene) -> &'static [Step] {
    match scene.steps.list {
        StepList::Chapters => STEPS,
        StepList::Playground => PLAYGROUND_STEPS,
    }
}

/// The chapter's starting point for a scene: its own settings with one lookup, no bias, no
/// culling, an orthographic light and the wrap its tutorial starts with.
pub fn start(scene: &Scene) -> ShadowSettings {
    ShadowSettings {
        technique: ShadowTechnique::Maps,
        filter: Filter::Single,
        bias_mode: BiasMode::None,
        cull: Cull::None,
        wrap: scene.steps.start_wrap,
        beyond_far: BeyondFar::Shadowed,
        light_projection: LightProjection::Ortho,
        show_depth_map: false,
        normal_offset: 0.0,
        polygon_offset: [0.0, 0.0],
        ..scene.shadow
    }
}

/// The settings of step `name` for `scene`: every earlier cumulative step of its list,
/// then this one.
pub fn settings_for(scene: &Scene, name: &str) -> Result<ShadowSettings> {
    let steps = of(scene);
    let index = steps.iter().position(|s| s.name == name).ok_or_else(|| {
        Error::Invalid(format!(
            "unknown step '{name}' for the {} scene (its [steps] list is \"{}\"): expected one \
             of {}",
            scene.name,
            scene.steps.list.name(),
            steps.iter().map(|s| s.name).collect::<Vec<_>>().join(", ")
        ))
    })?;
    let mut s = start(scene);
    for step in steps[..index].iter().filter(|s| s.cumulative) {
        (step.apply)(&mut s, &scene.steps);
    }
    (steps[index].apply)(&mut s, &scene.steps);
    Ok(s)
}

/// Every list's step names, each once (what `--step` takes; a scene takes its own list's).
pub fn names() -> Vec<&'static str> {
    let mut names: Vec<&'static str> = Vec::new();
    for step in STEPS.iter().chain(PLAYGROUND_STEPS) {
        if !names.contains(&step.name) {
            names.push(step.name);
        }
    }
    names
}

/// Step `name` of `scene`'s list.
pub fn get(scene: &Scene, name: &str) -> Option<&'static Step> {
    of(scene).iter().find(|s| s.name == name)
}
