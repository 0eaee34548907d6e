//! `history.csv`: a row per step of every stage (see [`HistoryRow`]), with a header, for
//! spreadsheets and pandas.

use crate::scene_file::HistoryRow;
use cloth_formats::atomic::write_atomically;
use std::path::Path;

pub fn write_history_csv(path: &Path, rows: &[HistoryRow]) -> std::io::Result<()> {
    write_atomically(path, |out| {
        let mut csv = csv::Writer::from_writer(out);
        for row in rows {
            csv.serialize(row).map_err(std::io::Error::other)?;
        }
        csv.flush()
    })
}
