//! Hunting big written-out input: a planar chain of 130 bodies written body by body (as a
//! CAD export or a script would write it), every tenth link heavier. rustc expands each of
//! the struct's attributes one level deeper, so past about 120 attributes the crate root
//! must raise `recursion_limit` (found: undocumented, the `scaling` report's spatial N = 128
//! failed on it; now in the crate docs and the report). Checked against the chain's
//! Lagrange equations in absolute angles written by hand.
#![recursion_limit = "256"]

use mbd::nalgebra::{DMatrix, DVector};
use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(b1, joint = revolute(q1), com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b2, parent = b1, joint = revolute(q2), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b3, parent = b2, joint = revolute(q3), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b4, parent = b3, joint = revolute(q4), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b5, parent = b4, joint = revolute(q5), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b6, parent = b5, joint = revolute(q6), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b7, parent = b6, joint = revolute(q7), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b8, parent = b7, joint = revolute(q8), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b9, parent = b8, joint = revolute(q9), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b10, parent = b9, joint = revolute(q10), at = [0.0, -l], com = [0.0, -l / 2.0], mass = 3.0 * m, inertia = 3.0 * m * l * l / 12.0)]
#[body(b11, parent = b10, joint = revolute(q11), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b12, parent = b11, joint = revolute(q12), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b13, parent = b12, joint = revolute(q13), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b14, parent = b13, joint = revolute(q14), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b15, parent = b14, joint = revolute(q15), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b16, parent = b15, joint = revolute(q16), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b17, parent = b16, joint = revolute(q17), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b18, parent = b17, joint = revolute(q18), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b19, parent = b18, joint = revolute(q19), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b20, parent = b19, joint = revolute(q20), at = [0.0, -l], com = [0.0, -l / 2.0], mass = 3.0 * m, inertia = 3.0 * m * l * l / 12.0)]
#[body(b21, parent = b20, joint = revolute(q21), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b22, parent = b21, joint = revolute(q22), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b23, parent = b22, joint = revolute(q23), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b24, parent = b23, joint = revolute(q24), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b25, parent = b24, joint = revolute(q25), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b26, parent = b25, joint = revolute(q26), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b27, parent = b26, joint = revolute(q27), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b28, parent = b27, joint = revolute(q28), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b29, parent = b28, joint = revolute(q29), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b30, parent = b29, joint = revolute(q30), at = [0.0, -l], com = [0.0, -l / 2.0], mass = 3.0 * m, inertia = 3.0 * m * l * l / 12.0)]
#[body(b31, parent = b30, joint = revolute(q31), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b32, parent = b31, joint = revolute(q32), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b33, parent = b32, joint = revolute(q33), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b34, parent = b33, joint = revolute(q34), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b35, parent = b34, joint = revolute(q35), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b36, parent = b35, joint = revolute(q36), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b37, parent = b36, joint = revolute(q37), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b38, parent = b37, joint = revolute(q38), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b39, parent = b38, joint = revolute(q39), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b40, parent = b39, joint = revolute(q40), at = [0.0, -l], com = [0.0, -l / 2.0], mass = 3.0 * m, inertia = 3.0 * m * l * l / 12.0)]
#[body(b41, parent = b40, joint = revolute(q41), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b42, parent = b41, joint = revolute(q42), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b43, parent = b42, joint = revolute(q43), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b44, parent = b43, joint = revolute(q44), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b45, parent = b44, joint = revolute(q45), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b46, parent = b45, joint = revolute(q46), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b47, parent = b46, joint = revolute(q47), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b48, parent = b47, joint = revolute(q48), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b49, parent = b48, joint = revolute(q49), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b50, parent = b49, joint = revolute(q50), at = [0.0, -l], com = [0.0, -l / 2.0], mass = 3.0 * m, inertia = 3.0 * m * l * l / 12.0)]
#[body(b51, parent = b50, joint = revolute(q51), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b52, parent = b51, joint = revolute(q52), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b53, parent = b52, joint = revolute(q53), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b54, parent = b53, joint = revolute(q54), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b55, parent = b54, joint = revolute(q55), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b56, parent = b55, joint = revolute(q56), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b57, parent = b56, joint = revolute(q57), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b58, parent = b57, joint = revolute(q58), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b59, parent = b58, joint = revolute(q59), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b60, parent = b59, joint = revolute(q60), at = [0.0, -l], com = [0.0, -l / 2.0], mass = 3.0 * m, inertia = 3.0 * m * l * l / 12.0)]
#[body(b61, parent = b60, joint = revolute(q61), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b62, parent = b61, joint = revolute(q62), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b63, parent = b62, joint = revolute(q63), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b64, parent = b63, joint = revolute(q64), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b65, parent = b64, joint = revolute(q65), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b66, parent = b65, joint = revolute(q66), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b67, parent = b66, joint = revolute(q67), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b68, parent = b67, joint = revolute(q68), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b69, parent = b68, joint = revolute(q69), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b70, parent = b69, joint = revolute(q70), at = [0.0, -l], com = [0.0, -l / 2.0], mass = 3.0 * m, inertia = 3.0 * m * l * l / 12.0)]
#[body(b71, parent = b70, joint = revolute(q71), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b72, parent = b71, joint = revolute(q72), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b73, parent = b72, joint = revolute(q73), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b74, parent = b73, joint = revolute(q74), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b75, parent = b74, joint = revolute(q75), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b76, parent = b75, joint = revolute(q76), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b77, parent = b76, joint = revolute(q77), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b78, parent = b77, joint = revolute(q78), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b79, parent = b78, joint = revolute(q79), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b80, parent = b79, joint = revolute(q80), at = [0.0, -l], com = [0.0, -l / 2.0], mass = 3.0 * m, inertia = 3.0 * m * l * l / 12.0)]
#[body(b81, parent = b80, joint = revolute(q81), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b82, parent = b81, joint = revolute(q82), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b83, parent = b82, joint = revolute(q83), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b84, parent = b83, joint = revolute(q84), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b85, parent = b84, joint = revolute(q85), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b86, parent = b85, joint = revolute(q86), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b87, parent = b86, joint = revolute(q87), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b88, parent = b87, joint = revolute(q88), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b89, parent = b88, joint = revolute(q89), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b90, parent = b89, joint = revolute(q90), at = [0.0, -l], com = [0.0, -l / 2.0], mass = 3.0 * m, inertia = 3.0 * m * l * l / 12.0)]
#[body(b91, parent = b90, joint = revolute(q91), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b92, parent = b91, joint = revolute(q92), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b93, parent = b92, joint = revolute(q93), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b94, parent = b93, joint = revolute(q94), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b95, parent = b94, joint = revolute(q95), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b96, parent = b95, joint = revolute(q96), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b97, parent = b96, joint = revolute(q97), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b98, parent = b97, joint = revolute(q98), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b99, parent = b98, joint = revolute(q99), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b100, parent = b99, joint = revolute(q100), at = [0.0, -l], com = [0.0, -l / 2.0], mass = 3.0 * m, inertia = 3.0 * m * l * l / 12.0)]
#[body(b101, parent = b100, joint = revolute(q101), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b102, parent = b101, joint = revolute(q102), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b103, parent = b102, joint = revolute(q103), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b104, parent = b103, joint = revolute(q104), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b105, parent = b104, joint = revolute(q105), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b106, parent = b105, joint = revolute(q106), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b107, parent = b106, joint = revolute(q107), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b108, parent = b107, joint = revolute(q108), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b109, parent = b108, joint = revolute(q109), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b110, parent = b109, joint = revolute(q110), at = [0.0, -l], com = [0.0, -l / 2.0], mass = 3.0 * m, inertia = 3.0 * m * l * l / 12.0)]
#[body(b111, parent = b110, joint = revolute(q111), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b112, parent = b111, joint = revolute(q112), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b113, parent = b112, joint = revolute(q113), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b114, parent = b113, joint = revolute(q114), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b115, parent = b114, joint = revolute(q115), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b116, parent = b115, joint = revolute(q116), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b117, parent = b116, joint = revolute(q117), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b118, parent = b117, joint = revolute(q118), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b119, parent = b118, joint = revolute(q119), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b120, parent = b119, joint = revolute(q120), at = [0.0, -l], com = [0.0, -l / 2.0], mass = 3.0 * m, inertia = 3.0 * m * l * l / 12.0)]
#[body(b121, parent = b120, joint = revolute(q121), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b122, parent = b121, joint = revolute(q122), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b123, parent = b122, joint = revolute(q123), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b124, parent = b123, joint = revolute(q124), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b125, parent = b124, joint = revolute(q125), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b126, parent = b125, joint = revolute(q126), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b127, parent = b126, joint = revolute(q127), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b128, parent = b127, joint = revolute(q128), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b129, parent = b128, joint = revolute(q129), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(b130, parent = b129, joint = revolute(q130), at = [0.0, -l], com = [0.0, -l / 2.0], mass = 3.0 * m, inertia = 3.0 * m * l * l / 12.0)]
pub struct Written130 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

const N: usize = 130;

/// Link `k`'s mass (0-based): every tenth (1-based) is three times heavier.
fn mass(m: f64, k: usize) -> f64 {
    if (k + 1).is_multiple_of(10) {
        3.0 * m
    } else {
        m
    }
}

/// The chain by hand in absolute angles `th_i` (relative `q` summed). Mass centre `k` is at
/// `sum_{j<k} l (sin th_j, -cos th_j) + l/2 (sin th_k, -cos th_k)`, so its derivative by `th_i`
/// is `a_ki l (cos th_i, sin th_i)` with `a_ki` = 1 (`i < k`), 1/2 (`i = k`), 0; with
/// `c_ij = sum_k m_k a_ki a_kj`, Lagrange's equations are
/// `sum_j l^2 c_ij (cos(th_i - th_j) th_j'' + sin(th_i - th_j) th_j'^2) + I_i th_i''
/// = -g l sin th_i sum_k m_k a_ki`. Returns the relative accelerations.
fn by_hand(m: f64, l: f64, g: f64, q: &[f64], qd: &[f64]) -> Vec<f64> {
    let cum = |v: &[f64]| -> Vec<f64> {
        v.iter()
            .scan(0.0, |s, x| {
                *s += x;
                Some(*s)
            })
            .collect()
    };
    let (th, thd) = (cum(q), cum(qd));
    let a = |k: usize, i: usize| match i.cmp(&k) {
        std::cmp::Ordering::Less => 1.0,
        std::cmp::Ordering::Equal => 0.5,
        std::cmp::Ordering::Greater => 0.0,
    };
    let c = |i: usize, j: usize| {
        (i.max(j)..N)
            .map(|k| mass(m, k) * a(k, i) * a(k, j))
            .sum::<f64>()
    };
    let cm = DMatrix::from_fn(N, N, c);
    let lhs = DMatrix::from_fn(N, N, |i, j| {
        let own = if i == j {
            mass(m, i) * l * l / 12.0
        } else {
            0.0
        };
        l * l * cm[(i, j)] * (th[i] - th[j]).cos() + own
    });
    let rhs = DVector::from_fn(N, |i, _| {
        let centripetal: f64 = (0..N)
            .map(|j| l * l * cm[(i, j)] * (th[i] - th[j]).sin() * thd[j] * thd[j])
            .sum();
        let load: f64 = (i..N).map(|k| mass(m, k) * a(k, i)).sum();
        -centripetal - g * l * th[i].sin() * load
    });
    let thdd = lhs.lu().solve(&rhs).unwrap();
    (0..N)
        .map(|k| thdd[k] - if k > 0 { thdd[k - 1] } else { 0.0 })
        .collect()
}

#[test]
fn a_chain_written_body_by_body_equals_its_equations_by_hand() {
    let p = Written130 {
        m: 0.8,
        l: 0.2,
        g: 9.81,
    };
    assert_eq!(Written130::COORDINATES.len(), N);
    for seed in [0.0, 1.7] {
        let q = Vector::<N>::from_fn(|i, _| 0.3 * (1.3 * i as f64 + seed).sin());
        let qd = Vector::<N>::from_fn(|i, _| 0.8 * (0.7 * i as f64 - seed).cos());
        let acc = p.acceleration(0.0, &q, &qd).unwrap();
        let want = by_hand(p.m, p.l, p.g, q.as_slice(), qd.as_slice());
        let scale = want.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        for k in 0..N {
            assert!(
                (acc[k] - want[k]).abs() < 1e-8 * scale,
                "q{}: {} against {}",
                k + 1,
                acc[k],
                want[k]
            );
        }
    }
}
