//! What users see of a contopt run, in one place: the charts, the table printed after a run
//! ([`table()`]), and the files a run's [`Report`](contopt_results::Report) becomes
//! ([`write()`]: `result.json`, the CSV files, the charts and, for a finite-element case, its
//! fields as VTK files for ParaView: [`vtu`]). It depends on the result types
//! of `contopt-results` only, not on the bodies or solvers that produced them.
//!
//! One unit per kind of quantity, as in `result.json`: pressures and stresses in MPa,
//! positions and sizes in mm, gaps, gap changes and displacements in µm; the CSV columns carry
//! the unit in their names as the JSON fields do (`p_mpa`, `x_mm`, `d_um`). A case is named by
//! its `label` in the table, the CSV files and the charts' legends alike.
//!
//! Charts — [`LineChart`] (with dashed reference curves: the closed form beside a computed
//! pressure), [`heat_map`] and [`section_map`] (a value over a grid of cells, with a colour
//! bar), [`log_log`] (benchmark panels) and [`BarChart`] (a bearing's lives per profile) — are drawn once, as SVG, by `plotters`, and the
//! PNG is that SVG rasterised by `resvg` ([`Figure::png`]). Both use one embedded font, so a
//! machine with no fonts installed draws the same picture. Ticks sit at round values
//! (1, 2, 5 × 10ᵏ), the axis descriptions carry units and are laid out from the measured
//! width of the tick labels so that neither overlaps nor is cut off, legends are the cases'
//! labels, in the paper's words as the scene writes them (`L1 = 20 mm`, `ν = 0.3`,
//! `E = 2·10⁵ MPa`; [`contopt_results::words`]), points that are not finite are skipped and a
//! one-value range is widened.
//!
//! ```
//! use contopt_report::LineChart;
//!
//! let hertz: Vec<(f64, f64)> = (0..=20)
//!     .map(|i| {
//!         let r = 0.05 * i as f64;
//!         (r, 100.0 * (1.0 - r * r).max(0.0).sqrt())
//!     })
//!     .collect();
//! let computed: Vec<(f64, f64)> = hertz.iter().map(|&(r, p)| (r, 0.98 * p)).collect();
//! let chart = LineChart::new("contact pressure", "r [mm]", "p [MPa]")
//!     .line("computed", &computed)
//!     .reference("Hertz", &hertz);
//! let figure = chart.draw()?;
//! assert!(figure.svg().contains("Hertz") && figure.svg().contains("p [MPa]"));
//! assert!(figure.png()?.starts_with(b"\x89PNG"));
//! # Ok::<(), std::io::Error>(())
//! ```
//!
//! **Why resvg for the PNG.** plotters can draw the PNG itself (its bitmap backend with its
//! `ab_glyph` font), and that compiles faster: a clean `cargo build --release` of a crate that
//! draws one chart both ways took 34 s (20 s of CPU) with plotters' bitmap backend and the
//! `png` crate, 80 s (56 s of CPU) with plotters' SVG and resvg, on the project's two-core
//! machine while other builds ran (`/usr/bin/time cargo build --release`). resvg is worth the
//! extra half-minute of a first build: its lines are anti-aliased, its text is laid out as in
//! the SVG (plotters' bitmap text misplaces glyphs: `L1 =  20 mm`), it renders at twice the
//! SVG's size ([`PNG_SCALE`]) for sharp figures, and the PNG cannot disagree with the SVG.

mod bars;
mod figure;
mod font;
mod line;
mod loglog;
mod map;
mod polar;
mod results;
mod scale;
mod style;
mod table;
mod ticks;
pub mod vtu;

pub use bars::BarChart;
pub use figure::{Figure, PNG_SCALE};
pub use line::LineChart;
pub use loglog::{log_log, Panel};
pub use map::{heat_map, section_map};
pub use results::{csv_field, write, write_cases, write_scene, Sink};
pub use table::table;
