//! `bouncemap fixed`: κ_c, every (1, k) solution with its classification and
//! eigenvalues, and the α window(s) of stability (birth α and α_PD).

use crate::config;
use crate::config::flags::FixedArgs;
use crate::output::records::{csv_writer, FixedDoc, FixedRow};
use crate::output::sink::Sink;
use crate::output::text::complex;
use crate::output::Format;
use bouncemap_engine::orbits::{fixed_point_slope, fixed_points, stability_windows};
use std::io::Write;

pub fn run(args: &FixedArgs) -> anyhow::Result<()> {
    let sys = config::system(&args.system)?;
    let points = fixed_points(&sys, args.k)?;
    let windows = stability_windows(sys.table(), sys.r(), args.k)?;
    let mut out = Sink::stdout();
    let written = (|| -> anyhow::Result<()> {
        match args.format {
            Format::Json => {
                let doc = FixedDoc::of(&sys, args.k, &points, &windows);
                serde_json::to_writer(&mut out, &doc)?;
                writeln!(out)?;
            }
            Format::Csv => {
                let mut w = csv_writer(&mut out, &FixedRow::HEADER)?;
                for p in &points {
                    w.serialize(FixedRow::from(p))?;
                }
                w.flush()?;
            }
            Format::Text => {
                writeln!(
                    out,
                    "table {}  alpha {}  r {}  k {}",
                    sys.table().name(),
                    sys.alpha(),
                    sys.r(),
                    args.k
                )?;
                writeln!(
                    out,
                    "kappa_c = {:.15}   (1,k) solutions need f'(t*) = {:.15}, v* = {}",
                    sys.kappa_c(),
                    fixed_point_slope(sys.r(), args.k),
                    0.5 * args.k as f64
                )?;
                if points.is_empty() {
                    writeln!(out, "no (1,{}) solution at this alpha", args.k)?;
                } else {
                    writeln!(
                        out,
                        "{:>18} {:>18} {:>18} {:>18}  {:>28} {:>28}  classification",
                        "phase", "f''", "f'''", "delta_kappa", "eigenvalue 1", "eigenvalue 2"
                    )?;
                    for p in &points {
                        writeln!(
                            out,
                            "{:>18.15} {:>18.12} {:>18.12} {:>18.12}  {:>28} {:>28}  {}",
                            p.phase,
                            p.ddf,
                            p.dddf,
                            p.delta_kappa,
                            complex(p.eigenvalues[0]),
                            complex(p.eigenvalues[1]),
                            p.classification.as_str()
                        )?;
                    }
                }
                if windows.is_empty() {
                    writeln!(out, "no alpha window with a stable (1,{}) solution", args.k)?;
                }
                for w in &windows {
                    writeln!(
                    out,
                    "stable for alpha in ({:.15}, {:.15}): born at phase {:.12}, ends by {} at phase {:.12}",
                    w.alpha_birth,
                    w.alpha_end,
                    w.phase_birth,
                    w.end.as_str(),
                    w.phase_end
                )?;
                }
                if let Some(pd) = windows.first().and_then(|w| w.alpha_pd()) {
                    writeln!(out, "alpha_PD = {pd:.15}")?;
                }
            }
        }
        Ok(())
    })();
    out.end(written)
}
