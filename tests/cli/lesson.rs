//! `dicesim tui --lesson FILE`: a teacher's lesson file is read before the explorer opens,
//! and one that cannot be walked is refused (exit status 2) naming its file, line and key.

use crate::common::dicesim_refused;

#[test]
fn tui_lesson_refuses_a_malformed_file_naming_its_line() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let cases = [
        // An unknown key on line 5.
        (
            "[[step]]\ntitle = \"Drop\"\nsay = \"Watch it fall.\"\npreset = \"paper\"\ncolour = \"red\"\n",
            "mine.toml:5:",
            "colour",
        ),
        // A preset that does not exist, on line 4.
        (
            "[[step]]\ntitle = \"Drop\"\nsay = \"Watch it fall.\"\npreset = \"no-such-preset\"\n",
            "mine.toml:4:",
            "no-such-preset",
        ),
        // A letter large type does not have, on line 3.
        (
            "[[step]]\ntitle = \"Spin\"\nsay = \"ω grows\"\npreset = \"paper\"\n",
            "mine.toml:3:",
            "`ω`",
        ),
    ];
    for (text, at, names) in cases {
        std::fs::write(dir.path().join("mine.toml"), text).expect("written");
        let stderr = dicesim_refused(dir.path(), &["tui", "--lesson", "mine.toml"]);
        assert!(stderr.contains(at) && stderr.contains(names), "{stderr}");
    }
    // A file that is not there is refused the same way.
    let stderr = dicesim_refused(dir.path(), &["tui", "--lesson", "absent.toml"]);
    assert!(stderr.contains("absent.toml"), "{stderr}");
}
