//! What `compare` and `compare --motion` share before any frame: the scene, its settings,
//! every check that needs no driver, then the context and the light's shadow plan.

use shadowmap::compare::{check_light, CompareOptions};
use shadowmap::engine::HeadlessContext;
use shadowmap::output::check_output_dir;
use shadowmap::shadows::plan::ShadowPlan;
use shadowmap::{Result, Scene, ShadowSettings};

use super::cli::CompareArgs;

/// A comparison ready to run: everything checked, the context made.
pub struct CompareSetup {
    pub scene: Scene,
    pub settings: ShadowSettings,
    pub context: HeadlessContext,
    pub plan: ShadowPlan,
    pub opts: CompareOptions,
}

impl CompareSetup {
    /// Loads and checks in the order a user's mistakes are cheapest to report: values,
    /// the light and the output folder before any GL work or file.
    pub fn prepare(args: &CompareArgs) -> Result<Self> {
        let (scene, settings) = args.scene.load_with(&args.settings)?;
        let (width, height) = args.scene.size(&scene);
        args.settings.check_values(&scene, &settings)?;
        check_light(&scene, args.light, "--light", true)?;
        check_output_dir("--out-dir", &args.out_dir)?;
        let context = HeadlessContext::new()?;
        let plan = args.settings.check(context.gl(), &scene, &settings)?;
        args.scene.check_size(context.gl(), &scene)?;
        let opts = CompareOptions {
            width,
            height,
            supersample: args.supersample,
            band: args.band,
            light: args.light,
            rays: args.rays,
        };
        Ok(Self {
            scene,
            settings,
            context,
            plan,
            opts,
        })
    }
}
