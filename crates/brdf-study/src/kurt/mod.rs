//! Kurt (2007) reproduced on CUReT and the Cornell paints: one file per
//! table or figure. Every number is computed in the run; Kurt's values are
//! printed beside ours. What several tables share is in [`common`], so a
//! table never imports this module back.

pub mod common;
pub mod figure_9_4;
pub mod figure_9_5;
pub mod lafortune_box;
pub mod ranked_figure;
pub mod table_9_1;
pub mod table_9_2;
pub mod table_9_4;
