//! The paper's figures as typed presets (`assets/presets/*.toml`, compiled into the
//! binary), and the one function that turns a preset into a sweep specification:
//! `sweep --preset`, `bench` and the terminal application's preset picker all call
//! [`Preset::sweep_spec`], so a preset means the same run everywhere.

use super::rules;
use super::table_spec::TableSpec;
use super::InputError;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::sweep::{InitialSpec, SweepSpec};
use serde::Deserialize;

/// Where each value of a preset starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Start {
    /// The default start (t̂0 = 0, a short hop): `--t0 --v0 --z0`.
    #[default]
    State,
    /// Slightly off the (1, 1) fixed point, as the paper does.
    NearFixedPoint,
}

/// A preset file.
#[derive(Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Preset {
    /// What the preset shows.
    pub description: String,
    #[serde(deserialize_with = "table_spec")]
    pub table: TableSpec,
    /// The swept parameter's name (`alpha`, `r`, or one of the table's, e.g. `D`).
    pub param: String,
    /// The swept window [lo, hi].
    pub window: [f64; 2],
    pub alpha: Option<f64>,
    pub r: Option<f64>,
    pub steps: usize,
    pub transient: u64,
    pub keep: usize,
    #[serde(default)]
    pub start: Start,
}

fn table_spec<'de, D: serde::Deserializer<'de>>(d: D) -> Result<TableSpec, D::Error> {
    let s = String::deserialize(d)?;
    TableSpec::parse(&s).map_err(serde::de::Error::custom)
}

/// The presets shipped with the binary: (name, file text).
pub const PRESETS: [(&str, &str); 9] = [
    ("fig3a", include_str!("../../assets/presets/fig3a.toml")),
    ("fig3b", include_str!("../../assets/presets/fig3b.toml")),
    ("fig3c", include_str!("../../assets/presets/fig3c.toml")),
    ("fig3d", include_str!("../../assets/presets/fig3d.toml")),
    ("fig3e", include_str!("../../assets/presets/fig3e.toml")),
    ("fig3f", include_str!("../../assets/presets/fig3f.toml")),
    ("fig4a", include_str!("../../assets/presets/fig4a.toml")),
    ("fig4b", include_str!("../../assets/presets/fig4b.toml")),
    ("fig4c", include_str!("../../assets/presets/fig4c.toml")),
];

/// The preset called `name`.
pub fn preset(name: &str) -> Result<Preset, InputError> {
    let text = PRESETS
        .iter()
        .find(|p| p.0 == name)
        .map(|p| p.1)
        .ok_or_else(|| {
            let names: Vec<&str> = PRESETS.iter().map(|p| p.0).collect();
            InputError(format!(
                "unknown preset {}: valid {}",
                crate::output::text::quoted(name),
                names.join(", ")
            ))
        })?;
    toml::from_str(text).map_err(|e| {
        InputError(format!(
            "preset {name}: {}",
            e.to_string().replace('\n', " ")
        ))
    })
}

/// Every preset, in order, with its name.
pub fn all() -> Vec<(String, Preset)> {
    PRESETS
        .iter()
        .map(|(name, _)| {
            (
                name.to_string(),
                preset(name).expect("shipped presets parse"),
            )
        })
        .collect()
}

impl Preset {
    /// The swept window's ends.
    pub fn window(&self) -> (f64, f64) {
        (self.window[0], self.window[1])
    }

    /// The sweep this preset runs, validated.
    pub fn sweep_spec(&self) -> Result<SweepSpec, InputError> {
        let table = self.table.load()?;
        let param = SweepParam::parse(&self.param, &table).map_err(InputError)?;
        let (lo, hi) = self.window();
        let mut spec = SweepSpec::new(
            table,
            self.alpha.unwrap_or(rules::ALPHA.default),
            self.r.unwrap_or(rules::R.default),
            param,
            lo,
            hi,
            self.steps,
        );
        spec.transient = self.transient;
        spec.keep = self.keep;
        spec.initial = InitialSpec {
            near_fixed_point: self.start == Start::NearFixedPoint,
            ..InitialSpec::default()
        };
        spec.validate()?;
        Ok(spec)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shipped_preset_gives_a_valid_sweep() {
        for (name, p) in all() {
            let spec = p.sweep_spec().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(spec.steps, p.steps, "{name}");
            assert!(
                spec.initial.near_fixed_point,
                "{name} starts as the paper does"
            );
        }
    }

    #[test]
    fn a_misspelt_parameter_is_refused_not_taken_for_d() {
        let text = PRESETS[0]
            .1
            .replace("param = \"alpha\"", "param = \"alfa\"");
        let p = toml::from_str::<Preset>(&text).unwrap();
        let e = p.sweep_spec().unwrap_err().0;
        assert!(e.contains("alfa") && e.contains("valid alpha, r, D"), "{e}");
    }
}
