//! turntable: a particle sliding with dry friction on a rotating table
//! (Agha, Gupta & Joseph, Am. J. Phys. 83, 126 (2015)).

pub mod script;
pub mod theme;
