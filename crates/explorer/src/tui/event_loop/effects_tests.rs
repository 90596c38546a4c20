//! The effects `update` asks for: exports written, animations sent, refusals said.

use crate::tui::tests::fixtures::press_performing;
use crate::tui::tests::fixtures::{mid_impact, screen, start};
use crate::worker::Command;
use dicesim_experiment::trace::{header, row};
use dicesim_physics::Simulation;
use ratatui::crossterm::event::KeyCode;

#[test]
fn e_exports_into_the_current_folder_and_p_switches_the_log_scale() {
    let mut a = start().app;
    assert_eq!(
        press_performing(&mut a, KeyCode::Char('e')),
        [Command::Export {
            dir: ".".into(),
            log_scale: false
        }]
    );
    assert!(!a.die_screen.log_scale);
    assert!(press_performing(&mut a, KeyCode::Char('p')).is_empty());
    assert!(a.die_screen.log_scale);
}

#[test]
fn the_exported_energy_plot_follows_the_screens_scale() {
    // `p` on screen, then `e`: the command carries the log scale to the export.
    let mut a = mid_impact().app;
    press_performing(&mut a, KeyCode::Char('p'));
    assert!(a.die_screen.log_scale);
    let c = press_performing(&mut a, KeyCode::Char('e'));
    assert!(
        matches!(c[..], [Command::Export { log_scale: true, .. }]),
        "{c:?}"
    );
    // The same roll exported on both scales: two different pictures (the export is
    // deterministic, so equal files would mean the scale was ignored).
    let png = |log_scale: bool| {
        let dir = tempfile::tempdir().expect("temp dir");
        let mut s = mid_impact();
        s.command(Command::Export {
            dir: dir.path().to_path_buf(),
            log_scale,
        });
        s.simulator.run_export_here();
        s.sync();
        std::fs::read(dir.path().join("dicesim-paper-preset-roll.png")).expect("png written")
    };
    let (linear, log) = (png(false), png(true));
    assert_eq!(linear, png(false), "an export is reproducible");
    assert_ne!(linear, log, "the log-scale export drew the linear plot");
}

#[test]
fn export_writes_the_whole_roll_as_csv_and_its_energy_plot_as_png() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = mid_impact();
    s.command(Command::Export {
        dir: dir.path().to_path_buf(),
        log_scale: false,
    });
    assert!(
        s.app.roll.export.is_some(),
        "the export runs off the worker's thread"
    );
    s.simulator.run_export_here();
    s.sync();
    let csv = dir.path().join("dicesim-paper-preset-roll.csv");
    let png = dir.path().join("dicesim-paper-preset-roll.png");
    let notice = s.app.notice.clone().expect("the status line says where");
    assert!(notice.contains(&csv.display().to_string()), "{notice}");
    // The roll again from t = 0 to its end, every step, in `dicesim trace`'s format.
    let text = std::fs::read_to_string(&csv).expect("csv written");
    let lines: Vec<&str> = text.lines().collect();
    let mut sim = Simulation::new(&s.app.setup.params, &s.app.setup.initial).expect("valid");
    let clock = dicesim_setup::number::StepClock::new(s.app.setup.params.integrator.dt);
    let first = row(&sim, &clock);
    let outcome = sim.run_to_end();
    assert_eq!(lines[0], header().join(","));
    assert_eq!(lines[1], first.join(","));
    assert_eq!(lines.len() as u64, outcome.steps + 2);
    assert_eq!(*lines.last().expect("rows"), row(&sim, &clock).join(","));
    // Its sidecar names the setup rolled.
    let meta = std::fs::read(dir.path().join("dicesim-paper-preset-roll.csv.meta.json")).expect("sidecar");
    let meta: serde_json::Value = serde_json::from_slice(&meta).expect("JSON");
    assert_eq!(meta["provenance"]["preset"]["name"], "paper");
    assert_eq!(meta["provenance"]["changed_from_preset"], false);
    let image = std::fs::read(&png).expect("png written");
    assert!(image.starts_with(b"\x89PNG\r\n\x1a\n") && image.len() > 10_000);
    // A second export replaces nothing.
    s.command(Command::Export {
        dir: dir.path().to_path_buf(),
        log_scale: false,
    });
    s.simulator.run_export_here();
    assert!(dir.path().join("dicesim-paper-preset-roll-2.csv").is_file());
    assert!(dir.path().join("dicesim-paper-preset-roll-2.png").is_file());
    assert_eq!(std::fs::read_to_string(&csv).expect("kept"), text);
}

#[test]
fn a_sends_the_animation_of_the_camera_s_view_and_the_status_line_follows_it() {
    let mut s = start();
    s.app.die_screen.camera.orbit(15.0, 10.0);
    let (yaw_deg, pitch_deg) = (s.app.die_screen.camera.yaw_deg, s.app.die_screen.camera.pitch_deg);
    assert_eq!(
        press_performing(&mut s.app, KeyCode::Char('A')),
        [Command::ExportAnimation {
            dir: ".".into(),
            yaw_deg,
            pitch_deg
        }]
    );
    // Ordered into a folder of its own: the status line tells the rolling and the
    // drawing, and the same key (or the roll's export key) cancels.
    let dir = tempfile::tempdir().expect("temp dir");
    s.command(Command::ExportAnimation {
        dir: dir.path().to_path_buf(),
        yaw_deg,
        pitch_deg,
    });
    let status = screen(&s.app, 120, 40);
    assert!(
        status.contains("exporting the animation: rolling, 0% of the time cap · A cancels"),
        "{status}"
    );
    s.app.roll.export = Some(crate::worker::ExportStatus::Animation(
        dicesim_figures::animation::AnimationProgress {
            drawing: true,
            done: 12,
            total: 80,
        },
    ));
    let status = screen(&s.app, 120, 40);
    assert!(
        status.contains("exporting the animation: frame 12 of 80 · A cancels"),
        "{status}"
    );
    assert_eq!(
        press_performing(&mut s.app, KeyCode::Char('A')),
        [Command::ExportCancel]
    );
    assert_eq!(
        press_performing(&mut s.app, KeyCode::Char('e')),
        [Command::ExportCancel]
    );
    s.command(Command::ExportCancel);
    assert_eq!(
        s.app.notice.as_deref(),
        Some("export cancelled: nothing was written")
    );
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    // Done: the status line says where it went.
    s.command(Command::ExportAnimation {
        dir: dir.path().to_path_buf(),
        yaw_deg,
        pitch_deg,
    });
    s.simulator.run_export_here();
    s.sync();
    let gif = std::fs::canonicalize(dir.path())
        .unwrap()
        .join("dicesim-paper-preset-roll.gif");
    assert!(
        gif.is_file(),
        "{:?}",
        std::fs::read_dir(dir.path()).unwrap().collect::<Vec<_>>()
    );
    let status = screen(&s.app, 160, 40);
    assert!(
        status.contains(&format!("animation saved to {}", gif.display())),
        "{status}"
    );
}

#[test]
fn export_into_a_missing_folder_says_why() {
    let mut s = start();
    s.command(Command::Export {
        dir: "/nonexistent/dicesim-export".into(),
        log_scale: false,
    });
    s.simulator.run_export_here();
    s.sync();
    let notice = s.app.notice.clone().expect("a notice");
    assert!(
        notice.starts_with("cannot export the roll: /nonexistent/dicesim-export/"),
        "{notice}"
    );
    assert!(notice.ends_with("does not exist"), "{notice}");
    assert!(s.app.roll.export.is_none(), "the export is over");
    assert!(!std::path::Path::new("/nonexistent/dicesim-export").exists());
}

#[test]
fn a_preset_name_never_leads_the_export_out_of_its_folder() {
    let root = tempfile::tempdir().expect("temp dir");
    let dir = root.path().join("a").join("b");
    std::fs::create_dir_all(&dir).unwrap();
    let mut s = start();
    let mut preset = s.simulator.preset().clone();
    preset.name = "x/../../escaped".to_string();
    s.command(Command::LoadPreset(Box::new(preset)));
    s.command(Command::Export {
        dir: dir.clone(),
        log_scale: false,
    });
    s.simulator.run_export_here();
    s.sync();
    let written: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        written.len(),
        3,
        "the trace, its sidecar and the plot: {written:?}"
    );
    assert!(
        written.contains(&"dicesim-x_______escaped-preset-roll.csv".to_string()),
        "{written:?}"
    );
    assert!(!root.path().join("escaped-preset-roll.csv").exists());
    assert_eq!(
        std::fs::read_dir(root.path()).unwrap().count(),
        1,
        "only a/ in the root"
    );
}

#[test]
fn a_trace_above_the_limit_is_refused_with_the_trace_every_alternative() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = start();
    // Δt = 1e-5 with no friction: millions of rows, gigabytes of trace.
    s.command(Command::SetParam(
        crate::tui::vocabulary::param::Param::named("ground.friction").scan_key(),
        0.0,
    ));
    s.command(Command::SetParam(
        crate::tui::vocabulary::param::Param::named("integrator.dt").scan_key(),
        1e-5,
    ));
    s.command(Command::Export {
        dir: dir.path().to_path_buf(),
        log_scale: false,
    });
    s.simulator.run_export_here();
    s.sync();
    let notice = s.app.notice.clone().expect("a notice");
    assert!(notice.contains("rows) is over the 268.4 MB limit"), "{notice}");
    assert!(notice.contains("`dicesim trace --every "), "{notice}");
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "nothing written"
    );
}
