//! A provenance states the setup as its preset file: the preset written from the provenance
//! of any shipped preset is read back and rolls every throw bit for bit as the original.

use dicesim_experiment::columns::same_record;
use dicesim_experiment::provenance;
use dicesim_experiment::record::{RollRecord, roll_record};
use dicesim_setup::preset::{Preset, SHIPPED, Store};
use dicesim_setup::random::RandomDraws;

/// The preset's own roll and `n` rolls drawn with `seed`.
fn rolls(preset: &Preset, seed: u64, n: u64) -> Vec<RollRecord> {
    let params = preset.params();
    let mut records = vec![roll_record(&params, &preset.initial, u64::MAX)];
    records.extend((0..n).map(|id| roll_record(&params, &preset.random.draw(&preset.initial, seed, id), id)));
    records
}

#[test]
fn the_preset_written_from_a_provenance_rolls_as_the_original() {
    let seed = 11;
    for (name, _) in SHIPPED {
        let (original, _) = Store::new(None).load(name).unwrap();
        let stated = provenance::batch(&original, Some(seed), 4, None)["preset"].clone();
        let file = toml::to_string(&stated).unwrap_or_else(|e| panic!("{name}: {e}"));
        let rebuilt = Preset::from_toml_str(&file, "the provenance's preset")
            .unwrap_or_else(|e| panic!("{name}: the provenance's preset is refused: {e}\n{file}"));
        // The seed the batch rolled is the rebuilt preset's own; the rest is the original.
        assert_eq!(rebuilt.random.seed, seed, "{name}");
        let mut reseeded = original.clone();
        reseeded.random.seed = seed;
        assert_eq!(rebuilt.to_json(), reseeded.to_json(), "{name}");
        let (a, b) = (rolls(&original, seed, 4), rolls(&rebuilt, seed, 4));
        for (a, b) in a.iter().zip(&b) {
            assert!(
                same_record(a, b),
                "{name}: {a:?} rolled again from its provenance is {b:?}"
            );
        }
    }
}
