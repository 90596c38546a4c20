//! The panels: each module draws one part of a screen from the state through one entry
//! point of one shape, `render(app: &App, area: Rect, frame: &mut Frame)`, and the table in
//! `render/places.rs` says where and when. A panel's parts too long for one function are
//! widgets of its own folder (`die/vectors.rs`, `quantity_plot/energy_chart.rs`), and its
//! tests live there too (`die/die_tests.rs`, with their `snapshots/`). Two modules here are
//! no panels but what several panels draw with: `chart` (axes, ticks and marks of the time
//! plots) and `overlays/popup` (a box cleared over the screen).

pub(crate) mod basin_map;
pub(crate) mod chart;
pub(crate) mod die;
pub(crate) mod footer;
pub(crate) mod header;
pub(crate) mod ledger;
pub(crate) mod outcomes;
pub(crate) mod overlays;
pub(crate) mod params_panel;
pub(crate) mod presentation;
pub(crate) mod quantity_plot;
pub(crate) mod timeline_strip;
pub(crate) mod too_small;
pub(crate) mod twins;
