//! The tutorials' steps as data: each step is a named preset of [`ShadowSettings`], built by
//! applying every earlier step's change to the tutorial's starting point. Nothing here
//! draws; the renderer is the same for every step. A scene names its list (`[steps] list`):
//! the chapters' ([`STEPS`]) or the shadow-playground's demo pages ([`PLAYGROUND_STEPS`]).
//! Where a tutorial's own view hides a step's change, the step carries a [`Stage`] for that
//! scene: its own camera or a small change of the scene, said in its caption.

use glam::Vec3;

use crate::error::{Error, Result};
use crate::scene::{Camera, Scene, StepContext, StepList};
use crate::settings::{
    BeyondFar, BiasMode, Blur, Cull, DepthLookup, Filter, LightProjection, MapSize, MsmToward,
    PerspectiveDepth, ShadowSettings, ShadowTechnique, Volumetric, Wrap,
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
    /// How the step is shown on the scenes whose own view hides its change (by scene name).
    pub stages: &'static [Stage],
    /// Scenes (by name) on which the step's picture is its predecessor's by design, and why.
    pub same_picture: &'static [(&'static str, &'static str)],
    apply: fn(&mut ShadowSettings, &StepContext),
}

/// A step's view of one scene: a camera of its own and small changes of the scene, so the
/// region its caption names is in the frame. The renderer is the same for every step.
pub struct Stage {
    /// The scene's name.
    pub scene: &'static str,
    /// What the stage changes, for the caption.
    pub note: &'static str,
    /// The camera's position and the point it looks at (the scene camera's lens kept).
    pub camera: Option<([f32; 3], [f32; 3])>,
    /// The first light's orthographic box: left, right, bottom, top, near, far.
    pub light_box: Option<[f32; 6]>,
    /// Items by name, each given a position and a scale.
    pub items: &'static [(&'static str, [f32; 3], [f32; 3])],
}

impl Step {
    /// The step's stage for `scene`, if it has one.
    pub fn stage(&self, scene: &Scene) -> Option<&'static Stage> {
        self.stages.iter().find(|s| s.scene == scene.name)
    }

    /// Why the step shows its predecessor's picture on `scene`, if it does by design.
    pub fn same_picture_on(&self, scene: &Scene) -> Option<&'static str> {
        self.same_picture
            .iter()
            .find(|(name, _)| *name == scene.name)
            .map(|(_, why)| *why)
    }

    /// Sets `scene` up as this step shows it: its stage's camera (unless `keep_camera`),
    /// light box and items. Nothing changes on a scene the step has no stage for.
    pub fn set_stage(&self, scene: &mut Scene, keep_camera: bool) -> Result<()> {
        let Some(stage) = self.stage(scene) else {
            return Ok(());
        };
        if let (Some((position, target)), false) = (stage.camera, keep_camera) {
            let at = Camera::look_at(position.into(), target.into()).ok_or_else(|| {
                Error::Invalid(format!("step {}: its camera looks at itself", self.name))
            })?;
            scene.camera.position = at.position;
            scene.camera.rotation = at.rotation;
        }
        let scene_name = scene.name.clone();
        if let Some([left, right, bottom, top, near, far]) = stage.light_box {
            let light = scene.light_mut().as_directional_mut().ok_or_else(|| {
                Error::Invalid(format!(
                    "step {}: its stage sets the light's box, but the {scene_name} scene's \
                     first light is not directional",
                    self.name
                ))
            })?;
            light.ortho = crate::scene::OrthoCoords {
                left,
                right,
                bottom,
                top,
                near,
                far,
            };
        }
        for (name, position, scale) in stage.items {
            let item = scene.items.iter_mut().find(|i| i.name == *name);
            let item = item.ok_or_else(|| {
                Error::Invalid(format!(
                    "step {}: its stage moves item '{name}', which the {scene_name} scene \
                     lacks",
                    self.name
                ))
            })?;
            item.position = Vec3::from(*position);
            item.scale = Vec3::from(*scale);
        }
        Ok(())
    }
}

/// The steps in the chapters' order (LWJGL "Shadows", LearnOpenGL "Shadow Mapping", the
/// slides' larger maps and perspective light, and the slides' closing shadow volumes).
pub const STEPS: &[Step] = &[
    Step {
        name: "depth-map",
        change: "The first pass only: the scene as the light sees it, stored as depth.",
        look_for: "Dark is near the light. The greys are stretched over the casters' depths \
                   (the range is under the picture) so that they can be told apart; \
                   a perspective map is linearised first.",
        cumulative: false,
        stages: &[],
        same_picture: &[],
        apply: |s, _| s.show_depth_map = true,
    },
    Step {
        name: "no-bias",
        change: "The plain comparison: a fragment is in shadow when it is farther from the \
                 light than the depth stored for its texel.",
        look_for: "Shadow acne: stripes of false shadow on every lit surface.",
        cumulative: true,
        stages: &[],
        same_picture: &[],
        apply: |s, _| s.bias_mode = BiasMode::None,
    },
    Step {
        name: "bias",
        change: "A constant bias is subtracted from the fragment's depth (the book 0.05, \
                 LearnOpenGL 0.005).",
        look_for: "The acne is gone; a large bias detaches shadows from their casters.",
        cumulative: true,
        stages: &[],
        same_picture: &[],
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
        stages: &[],
        same_picture: &[],
        apply: |s, _| {
            s.bias_mode = BiasMode::Slope;
            s.bias = 0.05;
            s.bias_min = 0.005;
        },
    },
    Step {
        name: "cull-front",
        change: "Front faces are culled in the depth pass (LearnOpenGL's text, the slides), so \
                 closed objects store their back faces: a lit face no longer meets its own \
                 depth, so it cannot have acne whatever the bias.",
        look_for: "The shadow lifts off where a caster rests on the floor. With the bias \
                   kept, the floor beside the caster now compares against its near back face \
                   (LearnOpenGL warns of casters close to their receiver), so the step is shown \
                   at such a contact. Single-sided geometry still casts only if wound to face \
                   away from the light.",
        cumulative: true,
        stages: &[
            Stage {
                scene: "dummy",
                note: "The DummyGame's cube is lowered to rest on the floor and seen from the \
                       side of its shadow, the contact in the middle.",
                camera: Some(([3.2, 1.2, -0.6], [0.0, -1.0, -1.0])),
                light_box: None,
                items: &[("cube", [0.0, -0.5, 0.0], [0.5, 0.5, 0.5])],
            },
            Stage {
                scene: "learnopengl",
                note: "Seen at the contact of the cube resting on the floor, from the side \
                       of its shadow and far enough back that the HUD covers no cube.",
                camera: Some(([4.8, 2.4, 4.4], [1.5, -0.3, 1.1])),
                light_box: None,
                items: &[],
            },
        ],
        same_picture: &[],
        apply: |s, _| s.cull = Cull::Front,
    },
    Step {
        name: "over-sampling-repeat",
        change: "The shadow map wraps with REPEAT (LearnOpenGL's first steps).",
        look_for: "False shadows outside the light's box: the map repeats across the floor. \
                   (Where the tutorial's box holds all that is seen, the step narrows it.)",
        cumulative: false,
        stages: OUTSIDE_THE_BOX,
        same_picture: &[(
            "learnopengl",
            "LearnOpenGL wraps with REPEAT from its first step, so the map has repeated \
             since then: this step names what the slope bias step already shows.",
        )],
        apply: |s, _| {
            s.wrap = Wrap::Repeat;
            s.beyond_far = BeyondFar::Shadowed;
        },
    },
    Step {
        name: "over-sampling-book",
        change: "The book's choice: CLAMP_TO_EDGE and no test past the far plane.",
        look_for: "Outside the box the edge texels repeat; beyond the far plane everything is \
                   shadowed. (Shown with the narrowed box of the step before.)",
        cumulative: false,
        stages: OUTSIDE_THE_BOX,
        same_picture: &[],
        apply: |s, _| {
            s.wrap = Wrap::ClampToEdge;
            s.beyond_far = BeyondFar::Shadowed;
        },
    },
    Step {
        name: "over-sampling",
        change: "LearnOpenGL's fix: clamp to a border of depth 1 and treat z > 1 as lit.",
        look_for: "Everything outside the light's box is lit (the narrowed box of the steps \
                   before).",
        cumulative: true,
        stages: OUTSIDE_THE_BOX,
        same_picture: &[],
        apply: |s, _| {
            s.wrap = Wrap::ClampToBorder;
            s.beyond_far = BeyondFar::Lit;
        },
    },
    Step {
        name: "pcf",
        change: "Percentage-closer filtering: the average of a 3 x 3 block of comparisons.",
        look_for: "Softer, less blocky shadow edges with intermediate values. Against the \
                   hard reference the error can rise: where the truth is 0 or 1, each grey of \
                   the ramp PCF spreads a texel or so either side of the edge is wrong by part \
                   of 1, on pixels the single lookup had right (the DummyGame at 640 x 360: \
                   MAE 0.0026 to 0.0050, half of it off the edge's own pixels). With texels \
                   no larger than pixels the ramp is under a pixel wide and PCF lowers it.",
        cumulative: true,
        stages: &[],
        same_picture: &[],
        apply: |s, _| s.filter = Filter::Pcf3x3,
    },
    Step {
        name: "hi-res",
        change: "A 4096 x 4096 shadow map (the slides go 2K, 4K, 8K).",
        look_for: "Sharper edges: each texel covers a sixteenth of the area.",
        cumulative: true,
        stages: &[],
        same_picture: &[],
        apply: |s, _| s.map_size = s.map_size.at_least(4096),
    },
    Step {
        name: "perspective",
        change: "A perspective light projection from the shadow position (the slides and the \
                 blog): a point-like light.",
        look_for: "Shadows spread out with distance from the light.",
        cumulative: false,
        stages: &[],
        same_picture: &[],
        apply: |s, _| {
            s.light_projection = LightProjection::Perspective;
            s.perspective_depth = PerspectiveDepth::Hyperbolic;
        },
    },
    Step {
        name: "perspective-depth-map",
        change: "The perspective light's depth map, linearised for display.",
        look_for: "Without linearising, everything past the nearest surfaces would be white. \
                   Front faces are still culled (`cull-front` carries over), so the map holds \
                   back faces: the cubes show their far faces, as if hollow, and a floor that \
                   faces the light (the DummyGame's) is not in it at all, white; one wound \
                   the other way (LearnOpenGL's) stays.",
        cumulative: false,
        stages: &[],
        same_picture: &[],
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
        stages: &[],
        same_picture: &[],
        apply: |s, _| s.technique = ShadowTechnique::Volumes,
    },
];

/// The over-sampling steps' view: the light's box narrowed so that floor lies outside it
/// (and, on the DummyGame, beyond its far plane), seen from far enough back.
const OUTSIDE_THE_BOX: &[Stage] = &[
    Stage {
        scene: "dummy",
        note: "The book's box (20 x 20, far 20) holds the DummyGame's whole floor, so it is \
               narrowed to 2.5 x 2.5 with far 7.2 and seen from above and aside: floor runs \
               past its sides, its front and, at the back, its far plane.",
        camera: Some(([2.2, 3.6, 2.2], [0.0, -1.0, -0.5])),
        light_box: Some([-1.25, 1.25, -1.25, 1.25, -1.0, 7.2]),
        items: &[],
    },
    Stage {
        scene: "learnopengl",
        note: "LearnOpenGL's box (20 x 20) is narrowed to 6 x 6, still around the three cubes, \
               and seen from high above: the floor outside it, where REPEAT tiles the cubes' \
               shadows 6 units apart, and beyond its far plane (7.5 units from the light) is \
               in view.",
        camera: Some(([1.0, 13.0, 1.0], [1.0, -0.5, 1.0])),
        light_box: Some([-3.0, 3.0, -3.0, 3.0, 1.0, 7.5]),
        items: &[],
    },
];

/// The shadow-playground's demo pages in its order (basic, PCF, soft PCF; its variance and
/// moment pages are filters of their own), then exponential shadow maps and PCSS, which the engines add, and its two
/// stages on summed-area tables of the moments (docs/techniques/soft-moments.md).
pub const PLAYGROUND_STEPS: &[Step] = &[
    Step {
        name: "basic",
        change: "The playground's basic demo: one comparison, shadowed when the fragment is \
                 more than its epsilon (5e-3) behind the stored depth. Its depth is a colour \
                 map read LINEAR, so the lookup compares a depth interpolated between four \
                 texels (depth_lookup = \"linear\"), as every page after it.",
        look_for: "Hard edges with the corners of the 400 x 300 map's texels cut diagonally.",
        cumulative: true,
        stages: &[],
        same_picture: &[],
        apply: |s, c| {
            s.filter = Filter::Single;
            s.bias_mode = BiasMode::Constant;
            s.bias = c.bias;
            s.depth_lookup = DepthLookup::Linear;
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
        stages: &[],
        same_picture: &[],
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
        stages: &[],
        same_picture: &[(
            "playground",
            "The sigmoid departs from the plain comparison only within a few thousandths of \
             depth of the stored value: here the frame differs from the PCF step's in a few \
             isolated pixels (the playground's two demos look alike too).",
        )],
        apply: |s, _| s.filter = Filter::SoftPcf,
    },
    Step {
        name: "variance",
        change: "Its variance demo: the map stores (z, z^2), blurred by its 3 x 3 Gaussian \
                 (0.045 / 0.122 / 0.332), and Chebyshev's bound gives the lit fraction \
                 (variance at least 1e-8, no bleeding reduction, and no epsilon: the demo \
                 subtracts no bias, the variance keeps acne away).",
        look_for: "Smooth edges from one filtered lookup; where the slab's shadow falls behind \
                   the cube's, light bleeds into it.",
        cumulative: true,
        stages: &[],
        same_picture: &[],
        apply: |s, _| {
            s.filter = Filter::Vsm;
            s.bias_mode = BiasMode::None;
            s.blur = Blur::Playground3x3;
            s.min_variance = 1e-8;
            s.bleed_reduction = 0.0;
        },
    },
    Step {
        name: "moment",
        change: "Its moment demo: (z, z^2, z^3, z^4), the same blur, the moments biased by \
                 9e-4 toward (0, 0.63, 0, 0.63), the Hamburger four-moment reconstruction; \
                 like the variance demo, no epsilon is subtracted from the fragment's depth.",
        look_for: "Edges as soft as the variance step's, with less light bleeding.",
        cumulative: true,
        stages: &[],
        same_picture: &[],
        apply: |s, _| {
            s.filter = Filter::Msm;
            s.msm_bias = 9e-4;
            s.msm_toward = MsmToward::Playground;
        },
    },
    Step {
        name: "esm",
        change: "Exponential shadow maps (Annen et al. 2008), past the playground's pages: one \
                 component, exp(40 z) (EVSM's positive exponent), the same blur; a receiver at \
                 d is lit by exp(-40 d) times the blurred value, which behind one caster at z \
                 is exp(-40 (d - z)).",
        look_for: "Edges as soft as the moment step's, from one float a texel where it keeps \
                   four; at the cube's foot a lit seam (blue in the error image): a caster \
                   within about 1/40 of the light's depth range of its receiver darkens it \
                   only partly (esm_exponent up to 88 narrows it).",
        cumulative: true,
        stages: &[],
        same_picture: &[],
        apply: |s, _| {
            s.filter = Filter::Esm;
            s.esm_exponent = 40.0;
        },
    },
    Step {
        name: "pcss",
        change: "Percentage-closer soft shadows (the engines' answer): a blocker search, then a \
                 filter as wide as the penumbra the light's size casts from that depth; the \
                 PCF pages' epsilon again, each lookup one texel (NEAREST), as the engines \
                 read their depth maps.",
        look_for: "Shadows sharp where the cube touches the slab and wider away from it, as the \
                   area-light truth's.",
        cumulative: true,
        stages: &[],
        same_picture: &[],
        apply: |s, _| {
            s.filter = Filter::Pcss;
            s.bias_mode = BiasMode::Constant;
            s.depth_lookup = DepthLookup::Nearest;
        },
    },
    Step {
        name: "vssm",
        change: "PCSS's two stages at a constant cost (variance soft shadow maps): summed-area \
                 tables of (z, z^2); the blocker search and a filter as wide as the penumbra \
                 each read 4 x 4 cells of texels, whatever the width, and test each cell \
                 against the receiver's plane by Chebyshev's bound. Like the variance page, no \
                 epsilon: the plane and the least variance keep acne away, and PCF's epsilon \
                 would move the receiver toward its blockers.",
        look_for: "Shadows sharp where the cube touches the slab and wider away from it, as \
                   PCSS's, with smooth penumbrae in place of its fine noise.",
        cumulative: true,
        stages: &[],
        same_picture: &[],
        apply: |s, _| {
            s.filter = Filter::Vssm;
            s.bias_mode = BiasMode::None;
        },
    },
    Step {
        name: "msm-soft",
        change: "The same on four moments (moment soft shadow maps), each cell by the \
                 Hamburger reconstruction, with the moment bias for [0, 1] depth (3e-5 toward \
                 0.5) in place of the moment page's 9e-4: a cell of a few texels needs \
                 little, and more lights the penumbra's dark side.",
        look_for: "The vssm step's penumbrae within a few levels, from four moments.",
        cumulative: true,
        stages: &[],
        same_picture: &[],
        apply: |s, _| {
            s.filter = Filter::MsmSoft;
            s.msm_bias = 3e-5;
            s.msm_toward = MsmToward::Half;
        },
    },
];

/// How translucent items cast (`[steps] list = "volumetric"`, the smoke scene): the two
/// wrongs of a depth map first.
pub const VOLUMETRIC_STEPS: &[Step] = &[
    Step {
        name: "volumetric-off",
        change: "Translucent items stay out of the depth map, as the chapters' depth pass \
                 would have it: they cast nothing.",
        look_for: "No shadow under the smoke or the glass; the cube's shadow alone.",
        cumulative: false,
        stages: &[],
        same_picture: &[(
            "smoke",
            "The smoke scene's own setting: the list starts from the scene as it is, and the \
             next step shows the other wrong.",
        )],
        apply: |s, _| s.volumetric = Volumetric::Off,
    },
    Step {
        name: "volumetric-solid",
        change: "Translucent items go into the depth map as if opaque.",
        look_for: "The smoke and the glass cast shadows as black as the cube's.",
        cumulative: false,
        stages: &[],
        same_picture: &[],
        apply: |s, _| s.volumetric = Volumetric::Solid,
    },
    Step {
        name: "volumetric-osm",
        change: "A translucent map beside the depth map: opacity shadow maps, 16 slices \
                 between the nearest and the farthest translucent caster, each crossing \
                 adding -ln(1 - opacity) to its slice; a receiver takes exp(-(what lies \
                 before it)).",
        look_for: "Grey shadows: the glass's passes half the light, the smoke's darkens where \
                   more puffs stack up; the cube's stays black.",
        cumulative: false,
        stages: &[],
        same_picture: &[],
        apply: |s, _| s.volumetric = Volumetric::Osm,
    },
    Step {
        name: "volumetric-fom",
        change: "Fourier opacity maps instead: the optical depth along the light as the mean \
                 and 7 cosine and sine terms, damped against ringing, in the same 64 bytes \
                 a texel.",
        look_for: "Behind the smoke and the glass the same grey as the slices give (exact \
                   behind every caster); within the smoke column the light falls off more \
                   smoothly.",
        cumulative: false,
        stages: &[],
        same_picture: &[],
        apply: |s, _| s.volumetric = Volumetric::Fom,
    },
    Step {
        name: "volumetric-avsm",
        change: "Adaptive volumetric shadow maps instead: per texel a curve of the light left \
                 against depth, 8 nodes in the same 64 bytes a texel, built from the \
                 translucent fragments peeled layer by layer from the light.",
        look_for: "The same greys behind the smoke and the glass (exact behind every caster); \
                   the smoke's edges as sharp as the slices give them.",
        cumulative: false,
        stages: &[],
        same_picture: &[],
        apply: |s, _| {
            s.volumetric = Volumetric::Avsm;
            s.avsm_nodes = 8;
        },
    },
];

/// The steps of `scene`'s list (`[steps] list`).
pub fn of(scene: &Scene) -> &'static [Step] {
    list(scene.steps.list)
}

/// The steps of one list.
fn list(list: StepList) -> &'static [Step] {
    match list {
        StepList::Chapters => STEPS,
        StepList::Playground => PLAYGROUND_STEPS,
        StepList::Volumetric => VOLUMETRIC_STEPS,
    }
}

/// Every list, in the order the help shows them.
const LISTS: [StepList; 3] = [
    StepList::Chapters,
    StepList::Playground,
    StepList::Volumetric,
];

/// The chapter's starting point for a scene: its own settings with one lookup, no bias, no
/// culling, an orthographic light and the wrap its tutorial starts with. The volumetric list
/// starts from the scene as it is: its lesson is what translucent casters do to a depth map
/// that already has its bias and filter.
pub fn start(scene: &Scene) -> ShadowSettings {
    if scene.steps.list == StepList::Volumetric {
        return scene.shadow;
    }
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

/// The built-in scenes that take `list` (their files' `[steps] list`, read from the text).
fn builtin_scenes_of(list: StepList) -> Vec<&'static str> {
    let list_of = |text: &str| -> StepList {
        let table: toml::Table = toml::from_str(text).unwrap_or_default();
        let named = table.get("steps").and_then(|s| s.get("list")).cloned();
        named.and_then(|l| l.try_into().ok()).unwrap_or_default()
    };
    crate::scene::BUILTIN_SCENES
        .iter()
        .filter(|(_, text)| list_of(text) == list)
        .map(|(name, _)| *name)
        .collect()
}

/// The scenes whose own view the chapters' staged steps (those with a [`Stage`]) are given.
pub const STAGED_SCENES: [&str; 2] = ["dummy", "learnopengl"];

/// Why the other scenes that take the chapters' list show those steps from their own view.
pub const UNSTAGED_WHY: &str = "The chapters' steps that need a view of their own \
    (cull-front: a caster resting on its receiver, seen at the contact; the over-sampling \
    steps: floor outside the light's box, which they narrow) have one on dummy and \
    learnopengl, the chapters' own scenes, whose boxes and casters the steps were written \
    for. The other scenes that take the chapters' list (slides, point-shadows, large, \
    three-lights, overlap, penumbra) draw every step from their own camera and light: \
    their first lights are spots and points with no box to narrow, or boxes fitted to \
    scenes made for other lessons (cascades, several lights, light bleeding, penumbrae), \
    so where a step's change lies outside their view their picture is the step before's.";

/// Which built-in scenes take which steps, from the lists themselves (for `--step`'s and
/// `steps`' help).
pub fn lists_help() -> String {
    let mut text = String::from("The steps each scene takes (its file's [steps] list):");
    for l in LISTS {
        let names: Vec<&str> = list(l).iter().map(|s| s.name).collect();
        text.push_str(&format!(
            "\n  {} (scenes {}):\n    {}",
            l.name(),
            builtin_scenes_of(l).join(", "),
            names.join(", ")
        ));
    }
    text.push_str("\n\n");
    text.push_str(UNSTAGED_WHY);
    text
}

/// Every list's step names, each once (what `--step` takes; a scene takes its own list's).
pub fn names() -> Vec<&'static str> {
    let mut names: Vec<&'static str> = Vec::new();
    for step in LISTS.iter().flat_map(|l| list(*l)) {
        if !names.contains(&step.name) {
            names.push(step.name);
        }
    }
    names
}

/// Sets `scene` up as step `name` is shown by every command ([`stage`]): from the scene's
/// steps camera with its steps' light size, then the step's own stage. `keep_camera` and
/// `keep_light_size`: a flag chose them.
pub fn show(scene: &mut Scene, name: &str, keep_camera: bool, keep_light_size: bool) -> Result<()> {
    if !keep_camera {
        scene.camera = scene.steps_camera();
    }
    if !keep_light_size {
        scene.use_steps_light_size();
    }
    match get(scene, name) {
        Some(step) => step.set_stage(scene, keep_camera),
        None => Ok(()),
    }
}

/// Step `name` as every command shows it (`render`, `demo` and its keys, `compare`,
/// `bench`, `soak`, `steps`): `scene` set up by [`show`], and the step's settings from
/// [`settings_for`]. The one meaning of a step: its view and its settings together.
pub fn stage(
    scene: &mut Scene,
    name: &str,
    keep_camera: bool,
    keep_light_size: bool,
) -> Result<ShadowSettings> {
    let settings = settings_for(scene, name)?;
    show(scene, name, keep_camera, keep_light_size)?;
    Ok(settings)
}

/// Step `name` of `scene`'s list.
pub fn get(scene: &Scene, name: &str) -> Option<&'static Step> {
    of(scene).iter().find(|s| s.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The chapters' scenes without views for the staged steps are each named where the
    /// help says why, and the staged scenes have a stage for every staged step.
    #[test]
    fn every_chapters_scene_has_the_staged_steps_views_or_is_named_in_why_not() {
        for name in builtin_scenes_of(StepList::Chapters) {
            let staged = STEPS.iter().filter(|s| !s.stages.is_empty());
            match STAGED_SCENES.contains(&name) {
                true => {
                    for step in staged {
                        assert!(step.stages.iter().any(|s| s.scene == name), "{name}");
                    }
                }
                false => assert!(UNSTAGED_WHY.contains(name), "{name}: {UNSTAGED_WHY}"),
            }
        }
        assert!(lists_help().ends_with(UNSTAGED_WHY));
    }
}
