// The INSA pull-out tank with a simple run-out anchorage, in plane strain (x along the pull,
// y up), for the continuum of fem/ (read by fem/tank_mesh.h). Regenerate the .msh with
//   gmsh -2 -format msh22 insa_tank_runout.geo -o insa_tank_runout.msh
// (change a dimension with -setnumber, e.g. -setnumber H 0.5).
//
// Dimensions: H (soil above the sheet, 0.40 m as in the calibration, or 0.50 m) and L (sheet
// length, 1 m in the calibration) are those of the reference paper (sections 2.2 and 4.3). The
// tank's inner length and the soil below the sheet are not in the extracted text (Figure 1 was
// lost): 1.5 m and 0.2 m are assumptions (those of the bundled inputs, examples/pullout_*.prm,
// so that their 'Continuum/mesh file' may name this mesh), to be replaced by the bench's drawing.
//
// Mesh: structured quadrilaterals (deal.II takes quads only), in four blocks so that the sheet's
// level y = base is a mesh line from x = tank_length - L to the front wall: the sheet's nodes can
// sit on cell edges. The sheet is not a physical line (it is inside the soil).
//
// Physical lines (boundary ids): 1 bottom, 2 front wall (x = tank_length, the sheet leaves the
// tank here), 3 top surface, 4 back wall (x = 0). Physical surface 1: the soil.

tank_length = DefineNumber[1.5, Name "tank length [m] (assumed)"];
base = DefineNumber[0.2, Name "soil below the sheet [m] (assumed)"];
H = DefineNumber[0.4, Name "soil above the sheet H [m]"];
L = DefineNumber[1.0, Name "sheet length L [m]"];
h = DefineNumber[0.025, Name "cell size [m]"];

x0 = tank_length - L;
top = base + H;

Point(1) = {0, 0, 0};
Point(2) = {x0, 0, 0};
Point(3) = {tank_length, 0, 0};
Point(4) = {0, base, 0};
Point(5) = {x0, base, 0};
Point(6) = {tank_length, base, 0};
Point(7) = {0, top, 0};
Point(8) = {x0, top, 0};
Point(9) = {tank_length, top, 0};

Line(1) = {1, 2};  Line(2) = {2, 3};    // bottom
Line(3) = {4, 5};  Line(4) = {5, 6};    // sheet level (4: the sheet)
Line(5) = {7, 8};  Line(6) = {8, 9};    // top
Line(7) = {1, 4};  Line(8) = {4, 7};    // back wall
Line(9) = {2, 5};  Line(10) = {5, 8};   // the sheet's far end, vertically
Line(11) = {3, 6}; Line(12) = {6, 9};   // front wall

Curve Loop(1) = {1, 9, -3, -7};   Plane Surface(1) = {1};
Curve Loop(2) = {2, 11, -4, -9};  Plane Surface(2) = {2};
Curve Loop(3) = {3, 10, -5, -8};  Plane Surface(3) = {3};
Curve Loop(4) = {4, 12, -6, -10}; Plane Surface(4) = {4};

Transfinite Curve{1, 3, 5} = Ceil(x0 / h) + 1;
Transfinite Curve{2, 4, 6} = Ceil(L / h) + 1;
Transfinite Curve{7, 9, 11} = Ceil(base / h) + 1;
Transfinite Curve{8, 10, 12} = Ceil(H / h) + 1;
Transfinite Surface{1, 2, 3, 4};
Recombine Surface{1, 2, 3, 4};

Physical Curve(1) = {1, 2};
Physical Curve(2) = {11, 12};
Physical Curve(3) = {5, 6};
Physical Curve(4) = {7, 8};
Physical Surface(1) = {1, 2, 3, 4};
