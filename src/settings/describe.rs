//! The settings' one-line summary, for window titles and reports.

use super::{
    BiasMode, Filter, Fit, LightProjection, MomentKnob, ShadowSettings, ShadowTechnique, Volumetric,
};

impl ShadowSettings {
    /// A short human summary, for window titles and reports: the map and its test, then
    /// every other field that differs from the defaults (the book's final configuration),
    /// so two settings that render differently never read the same. Fields that do nothing
    /// with the others (the fov of an orthographic light, the cascades' split of one map)
    /// are left out.
    pub fn summary(&self) -> String {
        if !self.shadows {
            return "no shadows".to_string();
        }
        if self.technique == ShadowTechnique::Volumes {
            let shown = if self.show_volumes {
                ", volumes shown"
            } else {
                ""
            };
            return format!("stencil shadow volumes (z-fail, depth clamp){shown}");
        }
        let bias = match self.bias_mode {
            BiasMode::None => "no bias".to_string(),
            BiasMode::Constant => format!("bias {}", self.bias),
            BiasMode::Slope => format!("slope bias {}..{}", self.bias_min, self.bias),
        };
        let size = self.map_size.label();
        let mut line = format!(
            "{size} {} {}, {}{}, cull {}",
            self.depth_format.name(),
            self.filter.name(),
            bias,
            self.offsets_and_layers(),
            self.cull.name()
        );
        // The rest by their serialised names and values, alphabetically (a new field shows
        // up here without being listed).
        let (Ok(serde_json::Value::Object(mine)), Ok(serde_json::Value::Object(base))) = (
            serde_json::to_value(self),
            serde_json::to_value(ShadowSettings::default()),
        ) else {
            return line;
        };
        for (key, value) in &mine {
            if base.get(key) == Some(value) {
                continue;
            }
            if let Some(part) = self.summary_part(key, value) {
                line.push_str(", ");
                line.push_str(&part);
            }
        }
        line
    }

    /// The summary's offsets and the split of a directional light's map (cascades or
    /// caster groups), each led by ", ".
    fn offsets_and_layers(&self) -> String {
        let mut extra = String::new();
        if self.normal_offset != 0.0 {
            extra.push_str(&format!(", normal offset {} texels", self.normal_offset));
        }
        if self.polygon_offset != [0.0, 0.0] {
            extra.push_str(&format!(
                ", polygon offset {}/{}",
                self.polygon_offset[0], self.polygon_offset[1]
            ));
        }
        let defaults = ShadowSettings::default();
        if self.cascades > 1 {
            extra.push_str(&format!(
                ", {} cascades (lambda {}",
                self.cascades, self.cascade_lambda
            ));
            if self.cascade_blend != defaults.cascade_blend {
                extra.push_str(&format!(", blend {}", self.cascade_blend));
            }
            if self.shadow_distance != defaults.shadow_distance {
                extra.push_str(&format!(", to depth {}", self.shadow_distance));
            }
            extra.push(')');
        } else if self.caster_groups > 1 {
            extra.push_str(&format!(", {} caster groups", self.caster_groups));
        }
        extra
    }

    /// How the summary names a field that differs from the default (by its serialised
    /// name); `None` for the fields shown before it or that do nothing with the others.
    fn summary_part(&self, key: &str, value: &serde_json::Value) -> Option<String> {
        let perspective = self.light_projection == LightProjection::Perspective;
        let fitted = self.fit == Fit::Scene || self.cascades > 1 || self.caster_groups > 1;
        let v = match value {
            serde_json::Value::String(s) => s.clone(),
            // Switches read as the flags spell them.
            serde_json::Value::Bool(b) => if *b { "on" } else { "off" }.to_string(),
            // Settings are f32: shown as f32 (0.4, not 0.4000000059604645).
            serde_json::Value::Number(n) if n.is_f64() => {
                (n.as_f64().unwrap_or_default() as f32).to_string()
            }
            other => other.to_string(),
        };
        Some(match key {
            "map_size" | "depth_format" | "filter" | "bias_mode" | "bias" | "bias_min"
            | "normal_offset" | "polygon_offset" | "cull" | "cascades" | "caster_groups"
            | "cascade_lambda" | "cascade_blend" | "shadow_distance" => return None,
            "perspective_fov" => return None,
            "pcss_blocker_taps" | "pcss_filter_taps" if self.filter != Filter::Pcss => return None,
            "depth_lookup" if self.filter.hardware() || self.filter.moments() => return None,
            // The moment maps' knobs do nothing where the filter's test does not read them.
            k if moment_knob(k).is_some_and(|g| !g.read_by(self.filter)) => return None,
            "osm_slices" if self.volumetric != Volumetric::Osm => return None,
            "fom_coefficients" if self.volumetric != Volumetric::Fom => return None,
            "avsm_nodes" | "peel_layers" if self.volumetric != Volumetric::Avsm => return None,
            "volumetric_size" if matches!(self.volumetric, Volumetric::Off | Volumetric::Solid) => {
                return None
            }
            "volumetric_size" => format!("translucent map {}", self.volumetric_size),
            "light_projection" if perspective => {
                format!("perspective light, fov {}", self.perspective_fov)
            }
            "light_projection" => format!("{v} light"),
            "light_view" => format!("{v} view"),
            "wrap" => format!("wrap {v}"),
            "beyond_far" => format!("beyond far {v}"),
            "fit" => format!("box fitted to the {v}"),
            "snap" if !fitted => return None,
            "snap" => "unsnapped".to_string(),
            "point_pass" => format!("point pass {v}"),
            "show_depth_map" => "showing the depth map".to_string(),
            "show_cascades" => "cascades tinted".to_string(),
            "show_volumes" => "volumes shown".to_string(),
            _ => format!("{} {v}", key.replace('_', " ")),
        })
    }
}

/// The moment maps' group that `setting` belongs to, if any.
fn moment_knob(setting: &str) -> Option<MomentKnob> {
    MomentKnob::ALL
        .into_iter()
        .find(|g| g.settings().contains(&setting))
}
