// The INSA pull-out tank with a wrap-around anchorage, in plane strain (x along the pull, y up),
// for the continuum of fem/ (read by fem/tank_mesh.h). Regenerate the .msh with
//   gmsh -2 -format msh22 insa_tank_wraparound.geo -o insa_tank_wraparound.msh
//
// The sheet (reference paper, section 2.2 and Figure 9): a lower part at depth H = D1 + D2 from
// the front wall back to x = tank_length - L, a vertical return of height D1, and an upper part of
// length B coming back towards the front at depth D2. Defaults: D1 = D2 = 0.2 m (H = 0.4 m),
// B = 0.25 m, as in the paper's simulations. The tank's inner length, the soil below the sheet
// and the length L of the lower part are not in the extracted text (Figure 1 was lost): 1.5 m,
// 0.2 m and 1 m are assumptions (those of examples/pullout_wraparound_h040_b025.prm, so that its
// 'Continuum/mesh file' may name this mesh), to be replaced by the bench's drawing.
//
// Mesh: structured quadrilaterals in 3 x 3 blocks whose edges carry the lower part (y = base),
// the return (x = tank_length - L) and the upper part (y = base + D1), so that the sheet's nodes
// can sit on cell edges. The sheet is not a physical line (it is inside the soil).
//
// Physical lines (boundary ids): 1 bottom, 2 front wall (x = tank_length, the sheet leaves the
// tank here), 3 top surface, 4 back wall (x = 0). Physical surface 1: the soil.

tank_length = DefineNumber[1.5, Name "tank length [m] (assumed)"];
base = DefineNumber[0.2, Name "soil below the sheet [m] (assumed)"];
D1 = DefineNumber[0.2, Name "return height D1 [m]"];
D2 = DefineNumber[0.2, Name "soil above the upper part D2 [m]"];
L = DefineNumber[1.0, Name "lower part length L [m] (assumed)"];
B = DefineNumber[0.25, Name "upper part length B [m]"];
h = DefineNumber[0.025, Name "cell size [m]"];

If (B >= L)
  Error("the upper part B = %g m must be shorter than the lower part L = %g m", B, L);
EndIf

xs[] = {0, tank_length - L, tank_length - L + B, tank_length};
ys[] = {0, base, base + D1, base + D1 + D2};

// Points p(i, j) = 1 + i + 4 j at (xs[i], ys[j]).
For j In {0:3}
  For i In {0:3}
    Point(1 + i + 4 * j) = {xs[i], ys[j], 0};
  EndFor
EndFor
// Horizontal lines 1 + i + 3 j (from p(i, j) to p(i + 1, j)), vertical lines 101 + i + 4 j (from
// p(i, j) to p(i, j + 1)).
For j In {0:3}
  For i In {0:2}
    Line(1 + i + 3 * j) = {1 + i + 4 * j, 2 + i + 4 * j};
    Transfinite Curve{1 + i + 3 * j} = Ceil((xs[i + 1] - xs[i]) / h) + 1;
  EndFor
EndFor
For j In {0:2}
  For i In {0:3}
    Line(101 + i + 4 * j) = {1 + i + 4 * j, 5 + i + 4 * j};
    Transfinite Curve{101 + i + 4 * j} = Ceil((ys[j + 1] - ys[j]) / h) + 1;
  EndFor
EndFor
For j In {0:2}
  For i In {0:2}
    Curve Loop(1 + i + 3 * j) = {1 + i + 3 * j, 102 + i + 4 * j, -(4 + i + 3 * j), -(101 + i + 4 * j)};
    Plane Surface(1 + i + 3 * j) = {1 + i + 3 * j};
    Transfinite Surface{1 + i + 3 * j};
    Recombine Surface{1 + i + 3 * j};
  EndFor
EndFor

Physical Curve(1) = {1, 2, 3};          // bottom
Physical Curve(2) = {104, 108, 112};    // front wall
Physical Curve(3) = {10, 11, 12};       // top
Physical Curve(4) = {101, 105, 109};    // back wall
Physical Surface(1) = {1:9};
