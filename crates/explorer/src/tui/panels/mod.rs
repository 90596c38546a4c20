//! The panels: each module draws one part of a screen from the state.

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
