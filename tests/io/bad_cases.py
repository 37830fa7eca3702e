"""Malformed model files and the one-line message each gives."""
import json
import tomllib

BASE = '''schema = 1
name = "fb"

[units]
length = "mm"
angle = "deg"

[points]
O2 = [0, 0]
A = [0, 100]
B = [261.506227, 247.018682]
O4 = [300, 0]

[[links]]
name = "ground"
points = ["O2", "O4"]
ground = true

[[links]]
name = "crank"
points = ["O2", "A"]
length = 100

[[links]]
name = "coupler"
points = ["A", "B"]

[[links]]
name = "rocker"
points = ["O4", "B"]

[[joints]]
type = "R"
links = ["ground", "crank"]
point = "O2"

[[joints]]
type = "R"
links = ["crank", "coupler"]
point = "A"

[[joints]]
type = "R"
links = ["coupler", "rocker"]
point = "B"

[[joints]]
type = "R"
links = ["ground", "rocker"]
point = "O4"

[[inputs]]
joint = "jO2"
range = [0, 360]
speed = 600
'''


def _replace(old: str, new: str) -> str:
    assert old in BASE, old
    return BASE.replace(old, new, 1)


_HEAD = BASE.split("[points]")[0]


def _sides(table: str) -> str:
    """BASE with a coupler point P at (100, 250) on the coupler A-B of length 300, given
    by ``sides = { <table> }``."""
    return (_replace('points = ["A", "B"]', f'points = ["A", "B", "P"]\nlength = 300\n'
                     f'sides = {{ {table} }}').replace('O4 = [300, 0]', 'O4 = [300, 0]\nP = [100, 250]'))
_SLIDER = ('[[links]]\nname = "slider"\npoints = ["B"]\n\n[[joints]]\ntype = "R"\n'
           'links = ["rocker", "slider"]\npoint = "B"\nname = "jBs"\n\n[[joints]]\nname = "s"\n'
           'type = "P"\nlinks = ["ground", "slider"]\npoint = "B"\n')
_FOURBAR = 'kind = "fourbar"\nground = 300\ncrank = 100\ncoupler = 300\n'

# (id, TOML text, the whole message: one line naming the file and the field)
CASES = [
    ("syntax: value missing", BASE + "\nx = \n",
     "fb.toml: line 57, column 5: TOML syntax error: invalid value; fix the syntax there"),
    ("syntax: key twice", _replace('name = "fb"', 'name = "fb"\nname = "x"'),
     "fb.toml: line 3, column 11: TOML syntax error: cannot overwrite a value; fix the syntax there"),
    ("syntax: newline in text", _replace('name = "fb"', 'name = "fb\n"'),
     "fb.toml: line 2, column 11: TOML syntax error: illegal character '\\n'; fix the syntax there"),
    ("syntax: unclosed table", BASE + "\n[outputs\n",
     "fb.toml: line 57, column 9: TOML syntax error: expected ']' at the end of a table "
     "declaration; fix the syntax there"),
    ("unknown top-level field", _replace('name = "fb"', 'nme = "fb"'),
     "fb.toml: nme: unknown field (did you mean 'name'?); valid fields are 'schema', 'name', "
     "'description', 'space', 'units', 'points', 'links', 'joints', 'inputs', 'sweep', "
     "'catalogue', 'outputs', 'dynamics', 'notation', 'spherical'"),
    ("unknown link field", _replace('ground = true', 'groud = true'),
     "fb.toml: links[0].groud: unknown field (did you mean 'ground'?); valid fields are 'name', "
     "'points', 'ground', 'length', 'local', 'sides', 'mass', 'center_of_mass', 'inertia'"),
    ("unknown units field", _replace('angle = "deg"', 'angle = "deg"\ntime = "s"'),
     "fb.toml: units.time: unknown field; valid fields are 'length', 'angle'"),
    ("gravity outside [dynamics]", 'gravity = [0, -9.81]\n' + BASE,
     "fb.toml: gravity: loads belong in the [dynamics] section (see docs/dynamics.md); move it there"),
    ("bad gravity in [dynamics]", BASE + '\n[dynamics]\ngravity = 9.81\n',
     "fb.toml: dynamics.gravity: expected two finite numbers (gx, gy) in m/s^2, got 9.81"),
    ("unknown point in a link", _replace('points = ["A", "B"]', 'points = ["A", "Q"]'),
     "fb.toml: links[2].points[1]: expected a declared point, got 'Q'; declared points are "
     "'O2', 'A', 'B', 'O4'"),
    ("unknown point of a joint", _replace('point = "O4"', 'point = "O5"'),
     "fb.toml: joints[3].point: expected a declared point, got 'O5'; declared points are "
     "'O2', 'A', 'B', 'O4'"),
    ("missing point of a joint", _replace('point = "B"\n', ''),
     "fb.toml: joints[2].point: missing; a joint of type 'R' needs the point where it acts"),
    ("unknown link of a joint", _replace('links = ["ground", "rocker"]', 'links = ["ground", "roker"]'),
     "fb.toml: joints[3].links[1]: expected a declared link, got 'roker' (did you mean "
     "'rocker'?); declared links are 'ground', 'crank', 'coupler', 'rocker'"),
    ("unknown joint of an input", _replace('joint = "jO2"', 'joint = "jO3"'),
     "fb.toml: inputs[0].joint: expected a declared joint, got 'jO3' (did you mean 'jO4'?); "
     "declared joints are 'jO2', 'jA', 'jB', 'jO4'"),
    ("coordinates of the wrong type", _replace('A = [0, 100]', 'A = [0, "100"]'),
     "fb.toml: points.A: expected [x, y], got [0, '100']"),
    ("three coordinates in the plane", _replace('A = [0, 100]', 'A = [0, 100, 0]'),
     "fb.toml: points.A: expected [x, y], got [0, 100, 0]"),
    ("a boolean coordinate", _replace('A = [0, 100]', 'A = [0, true]'),
     "fb.toml: points.A: expected [x, y], got [0, true]"),
    ("an infinite coordinate", _replace('A = [0, 100]', 'A = [0, inf]'),
     "fb.toml: points.A: expected finite numbers, got [0, inf]"),
    ("link points as text", _replace('points = ["O4", "B"]', 'points = "O4"'),
     "fb.toml: links[3].points: expected a list of points, got 'O4'"),
    ("ground not a boolean", _replace('ground = true', 'ground = "yes"'),
     "fb.toml: links[0].ground: expected true or false, got 'yes'"),
    ("non-positive length", _replace('length = 100', 'length = -100'),
     "fb.toml: links[1].length: expected a positive length, got -100 mm"),
    # by hand: 1000 > 300 + 250 + 300, the sketch's other bars
    ("lengths that cannot close", _replace('length = 100', 'length = 1000'),
     # the true gap: a loop of bars misses by its longest bar's excess over the others
     "fb.toml: links[1].length: no assembly: the loop O2-O4-B-A cannot close; it misses by 150 mm: "
     "its longest bar is longer than the others together: crank 1000 mm > ground 300 + rocker 250 "
     "+ coupler 300 = 850 mm; shorten crank to at most 850 mm or lengthen the others"),
    ("a place for the link's first point", _replace('length = 100', 'length = 100\nlocal = { O2 = [1, 2] }'),
     "fb.toml: links[1].local.O2: expected one of the link's points after its first two (none), "
     "got 'O2'"),
    ("a place that is not two numbers", _replace('name = "coupler"\npoints = ["A", "B"]',
                                                  'name = "coupler"\npoints = ["A", "B", "O4"]\n'
                                                  'local = { O4 = [1] }'),
     "fb.toml: links[2].local.O4: expected a place [along, left], got [1]"),
    # a coupler point P given by its sides from A and B, which the sketch puts 300 mm apart
    ("sides that make no triangle", _sides('P = { A = 30, B = 10, side = "left" }'),
     "fb.toml: links[2].sides.P: 'P' cannot be 30 mm from 'A' and 10 mm from 'B': 'A' and 'B' "
     "are 300 mm apart; the sides must satisfy |dA - dB| <= AB <= dA + dB; change a distance"),
    # by hand: |400 - 50| = 350 > 300
    ("sides whose difference is too long", _sides('P = { A = 400, B = 50, side = "left" }'),
     "fb.toml: links[2].sides.P: 'P' cannot be 400 mm from 'A' and 50 mm from 'B': 'A' and 'B' "
     "are 300 mm apart; the sides must satisfy |dA - dB| <= AB <= dA + dB; change a distance"),
    ("a side of zero", _sides('P = { A = 0, B = 200, side = "left" }'),
     "fb.toml: links[2].sides.P.A: expected a positive length, got 0 mm"),
    ("a negative side", _sides('P = { A = 200, B = -200, side = "left" }'),
     "fb.toml: links[2].sides.P.B: expected a positive length, got -200 mm"),
    ("an infinite side", _sides('P = { A = inf, B = 200, side = "left" }'),
     "fb.toml: links[2].sides.P.A: expected a finite number, got inf"),
    ("a side of nan", _sides('P = { A = nan, B = 200, side = "left" }'),
     "fb.toml: links[2].sides.P.A: expected a finite number, got nan"),
    ("a side as text", _sides('P = { A = "200", B = 200, side = "left" }'),
     "fb.toml: links[2].sides.P.A: expected a number, got '200'"),
    ("a side out of scale", _sides('P = { A = 1e300, B = 200, side = "left" }'),
     "fb.toml: links[2].sides.P.A: expected a length from 1e-09 m to 1e+09 m, got 1e+300 mm"),
    ("an unknown side word", _sides('P = { A = 200, B = 200, side = "lft" }'),
     "fb.toml: links[2].sides.P.side: expected one of 'left', 'right', got 'lft' (did you mean "
     "'left'?)"),
    ("no side for a triangle that has two", _sides('P = { A = 200, B = 200 }'),
     "fb.toml: links[2].sides.P.side: missing; 'P' may lie left or right of the line A -> B; say "
     "which: side = 'left' or 'right'"),
    ("a point in local and in sides", _sides('P = { A = 200, B = 200, side = "left" }')
     .replace('length = 300', 'length = 300\nlocal = { P = [150, 100] }'),
     "fb.toml: links[2].sides.P: 'P' is given in local too; give its place one way: remove it "
     "from local or from sides"),
    ("a side from a point off the link", _sides('P = { A = 200, O4 = 200, side = "left" }'),
     "fb.toml: links[2].sides.P.O4: expected one of the link's points placed before 'P' ('A', "
     "'B'), got 'O4'; points are placed in the order of the link's points"),
    ("a side from a point placed later", _sides('P = { A = 200, Q = 200, side = "left" }')
     .replace('points = ["A", "B", "P"]', 'points = ["A", "B", "P", "Q"]')
     .replace('O4 = [300, 0]', 'O4 = [300, 0]\nQ = [100, 300]'),
     "fb.toml: links[2].sides.P.Q: expected one of the link's points placed before 'P' ('A', "
     "'B'), got 'Q'; points are placed in the order of the link's points"),
    ("a side from one point only", _sides('P = { A = 200, side = "left" }'),
     "fb.toml: links[2].sides.P: expected the distances from two points of the link placed "
     "before 'P' ('A', 'B'), such as {A = 30, B = 40, side = 'left'}, got 1 ('A')"),
    ("sides for the link's first point", _sides('A = { B = 200, P = 200, side = "left" }'),
     "fb.toml: links[2].sides.A: expected one of the link's points after its first two ('P'), "
     "got 'A', its first point, which the link's frame places"),
    ("sides for the link's second point", _sides('B = { A = 300, P = 200, side = "left" }'),
     "fb.toml: links[2].sides.B: expected one of the link's points after its first two ('P'), "
     "got 'B', its second point, which the link's frame places"),
    ("sides as a list", _sides('P = [200, 200, "left"]'),
     "fb.toml: links[2].sides.P: expected a table {A = distance, B = distance, side = \"left\" "
     "or \"right\"} of its distances from two points of the link placed before it, got [200, "
     "200, 'left']"),
    # by hand: the ground O2-O4-G is the frame (O4 300 mm along +x); the sides put G at
    # along = (150^2 - 250^2 + 300^2) / 600 = 83.3333, left = sqrt(150^2 - 83.3333^2) = 124.722,
    # which is hypot(100 - 83.3333, 100 - 124.722) = 29.8153 from where the sketch puts it
    ("a ground point off its sides", _replace('points = ["O2", "O4"]', 'points = ["O2", "O4", "G"]\n'
                                             'sides = { G = { O2 = 150, O4 = 250, side = "left" } }')
     .replace('O4 = [300, 0]', 'O4 = [300, 0]\nG = [100, 100]'),
     "fb.toml: links[0].sides.G: the ground's points are the frame and are not moved, but the "
     "sketch puts 'G' 29.8153 mm from where its sides place it, (83.3333, 124.722 mm); move 'G' "
     "there "
     "or correct its sides"),
    ("an offset on a pin", _replace('point = "O2"', 'point = "O2"\noffset = 3'),
     "fb.toml: joints[0].offset: only a prismatic joint has one (the distance of its slide line "
     "from its origin); remove it"),
    ("non-positive mass", _replace('length = 100', 'length = 100\nmass = 0'),
     "fb.toml: links[1].mass: expected a positive number, got 0"),
    ("centre of mass off the link", _replace('length = 100', 'length = 100\ncenter_of_mass = "B"'),
     "fb.toml: links[1].center_of_mass: expected a declared point, got 'B'; the link's points "
     "are 'O2', 'A'"),
    ("unknown length unit", _replace('length = "mm"', 'length = "mmm"'),
     "fb.toml: units.length: expected one of 'm', 'cm', 'mm', 'in', got 'mmm' (did you mean 'mm'?)"),
    ("unknown angle unit", _replace('angle = "deg"', 'angle = "degree"'),
     "fb.toml: units.angle: expected one of 'rad', 'deg', got 'degree' (did you mean 'deg'?)"),
    ("units missing", _replace('[units]\nlength = "mm"\nangle = "deg"\n', ''),
     "fb.toml: units: missing; say which units the file is written in, e.g. [units] length = "
     "\"mm\", angle = \"deg\""),
    ("schema missing", _replace('schema = 1\n', ''),
     "fb.toml: schema: missing; add schema = 1 at the top of the file"),
    ("schema from the future", _replace('schema = 1', 'schema = 2'),
     "fb.toml: schema: this file is written for schema 2, but this kinelab reads schema 1 and "
     "older; upgrade kinelab"),
    ("schema of a hundred digits", _replace('schema = 1', 'schema = ' + '9' * 100),
     "fb.toml: schema: this file is written for schema a whole number of 100 digits, but "
     "this kinelab reads schema 1 and older; upgrade kinelab"),
    ("schema not a number", _replace('schema = 1', 'schema = "1"'),
     "fb.toml: schema: expected a whole number from 1 to 1, got '1'"),
    ("unknown joint type", _replace('type = "R"\nlinks = ["ground", "rocker"]',
                                    'type = "Q"\nlinks = ["ground", "rocker"]'),
     "fb.toml: joints[3].type: expected one of 'R', 'P', 'H', 'C', 'U', 'S', 'E', 'cam', 'gear', "
     "'G', 'rolling', 'pin_in_slot', got 'Q'"),
    ("prismatic joint without an axis", _replace('[[inputs]]', _SLIDER + '\n[[inputs]]'),
     "fb.toml: joints[5].axis: a P joint needs an axis"),
    ("zero axis", _replace('[[inputs]]', _SLIDER + 'axis = [0, 0]\n\n[[inputs]]'),
     "fb.toml: joints[5].axis: expected a direction, got the zero vector"),
    ("axis angle beyond the turns", _replace('[[inputs]]', _SLIDER + 'axis = 1e300\n\n[[inputs]]'),
     "fb.toml: joints[5].axis: expected angles within 1000 turns of 0 either way, got 1e+300"),
    ("axis as text", _replace('[[inputs]]', _SLIDER + 'axis = "x"\n\n[[inputs]]'),
     "fb.toml: joints[5].axis: expected an angle (deg) or a direction [x, y], got 'x'"),
    ("input range of one number", _replace('range = [0, 360]', 'range = [0]'),
     "fb.toml: inputs[0].range: expected 2 numbers, got [0]"),
    ("empty input range", _replace('range = [0, 360]', 'range = [10, 10]'),
     "fb.toml: inputs[0].range: start and stop are equal (10 deg); give an interval"),
    ("too few samples", _replace('speed = 600', 'speed = 600\nsamples = 1'),
     "fb.toml: inputs[0].samples: expected a whole number from 2 to 1,000,000, got 1"),
    ("speed as text", _replace('speed = 600', 'speed = "fast"'),
     "fb.toml: inputs[0].speed: expected a number, got 'fast'"),
    ("speed not a number", _replace('speed = 600', 'speed = nan'),
     "fb.toml: inputs[0].speed: expected a finite number, got nan"),
    ("input with joint and links", _replace('joint = "jO2"', 'joint = "jO2"\nlinks = ["ground", "crank"]'),
     "fb.toml: inputs[0]: expected either joint = \"name\" or links = [\"a\", \"b\"]"),
    ("two ground links", _replace('name = "crank"', 'name = "crank"\nground = true'),
     "fb.toml: links: expected exactly one ground link, got 2 ('ground', 'crank'); mark one "
     "link ground = true"),
    ("no ground link", _replace('ground = true\n', ''),
     "fb.toml: links: expected exactly one ground link, got 0; mark one link ground = true"),
    ("a name used twice", _replace('point = "O4"', 'point = "O4"\nname = "A"'),
     "fb.toml: joints[3].name: 'A' is already the name of points.A; names must be unique across "
     "points, links and joints"),
    ("a link name used twice", _replace('name = "rocker"\npoints = ["O4", "B"]',
                                        'name = "rocker"\npoints = ["O4", "B"]\n\n[[links]]\n'
                                        'name = "rocker"\npoints = ["O4", "B"]'),
     "fb.toml: links[4].name: 'rocker' is already the name of links[3]; names must be unique "
     "across points, links and joints"),
    ("link of no length", _replace('A = [0, 100]', 'A = [0, 0]'),
     "fb.toml: links[1]: its first two points 'O2' and 'A' coincide, so the link has no length "
     "and no direction; move one of them"),
    ("links not hinged at a shared point",
     _replace('[[joints]]\ntype = "R"\nlinks = ["crank", "coupler"]\npoint = "A"\n', ''),
     "fb.toml: points.A: carried by 'crank', 'coupler', which are not all joined by revolute "
     "joints at 'A'; add the joints or give each link its own point"),
    ("unknown space", _replace('name = "fb"', 'name = "fb"\nspace = "plane"'),
     "fb.toml: space: expected one of 'planar', 'spherical', 'spatial', got 'plane' (did you "
     "mean 'planar'?)"),
    ("unknown sweep", _replace('name = "fb"', 'name = "fb"\nsweep = "grid3"'),
     "fb.toml: sweep: expected one of 'together', 'grid', got 'grid3' (did you mean 'grid'?)"),
    ("name not text", _replace('name = "fb"', 'name = 3'),
     "fb.toml: name: expected a non-empty text, got 3"),
    ("unknown output", BASE + '\n[outputs]\nreport = ["rockr"]\n',
     "fb.toml: outputs.report[0]: expected a declared link, point or slide, got 'rockr' (did you "
     "mean 'rocker'?); its links, points and slides are 'ground', 'crank', 'coupler', 'rocker', "
     "'O2', 'A', 'B', 'O4'"),
    ("transmission of one link", BASE + '\n[outputs]\ntransmission = ["coupler"]\n',
     "fb.toml: outputs.transmission[0]: expected 2 links, got ['coupler']"),
    ("catalogue: unknown kind", _HEAD + '[catalogue]\nkind = "fourbars"\n',
     "fb.toml: catalogue.kind: expected one of 'fourbar', 'slider_crank', 'inverted_slider_crank', "
     "'slotted_link', 'whitworth', 'fivebar', 'watt6', 'stephenson6', 'triad6', got 'fourbars' "
     "(did you mean 'fourbar'?)"),
    ("catalogue: negative length", _HEAD + '[catalogue]\n' + _FOURBAR.replace("100", "-100")
     + 'rocker = 250\n', "fb.toml: catalogue.crank: expected a positive length, got -100 mm"),
    ("catalogue: unknown parameter", _HEAD + '[catalogue]\n' + _FOURBAR + 'rocker = 250\nrockr = 2\n',
     "fb.toml: catalogue.rockr: unknown field (did you mean 'rocker'?); valid fields are 'kind', "
     "'ground', 'crank', 'coupler', 'rocker', 'coupler_point', 'branch'"),
    ("catalogue: missing parameter", _HEAD + '[catalogue]\n' + _FOURBAR,
     "fb.toml: catalogue.rocker: missing; a fourbar needs it"),
    ("catalogue: lengths that never close", _HEAD + '[catalogue]\nkind = "fourbar"\nground = 3000\n'
     'crank = 100\ncoupler = 100\nrocker = 100\n',
     "fb.toml: catalogue: fourbar: these lengths cannot be assembled at any input angle; check them"),
    ("catalogue: unknown branch", _HEAD + '[catalogue]\n' + _FOURBAR + 'rocker = 250\nbranch = "cross"\n',
     "fb.toml: catalogue.branch: expected one of 'open', 'crossed', got 'cross' (did you mean "
     "'crossed'?)"),
    ("catalogue: six-bar length on no link", _HEAD + '[catalogue]\nkind = "watt6"\n'
     'lengths = { "A-C" = 1000 }\n',
     "fb.toml: catalogue.lengths['A-C']: A and C are not on one link; expected one of 'O2-A', "
     "'A-B', 'O4-B', 'O4-C', 'B-C', 'C-D', 'O6-D'"),
    ("catalogue: six-bar length not positive", _HEAD + '[catalogue]\nkind = "watt6"\n'
     'lengths = { "O2-A" = 0 }\n',
     "fb.toml: catalogue.lengths.O2-A: expected a positive length, got 0 mm"),
    ("catalogue: six-bar lengths not a table", _HEAD + '[catalogue]\nkind = "stephenson6"\n'
     'lengths = [1000, 2000]\n',
     'fb.toml: catalogue.lengths: expected a table of "X-Y" = length, got [1000, 2000]'),
    # in the file's unit: |O2 O4| - |O2 A| = 5681.065 - 999.978 mm (checked by hand)
    ("catalogue: six-bar dyad that never closes", _HEAD + '[catalogue]\nkind = "watt6"\n'
     'lengths = { "A-B" = 500, "O4-B" = 4000 }\n',
     "fb.toml: catalogue.lengths: dyad A-B-O4 closes at no crank angle: expected A-B + O4-B >= "
     "4681.09 mm, the closest A comes to O4 over a turn of the crank, got 4500 mm; lengthen A-B "
     "or O4-B"),
    ("catalogue: six-bar branch not a pair", _HEAD + '[catalogue]\nkind = "watt6"\nbranch = "open"\n',
     "fb.toml: catalogue.branch: expected a pair of 'open'/'crossed', one per dyad (A-B-O4, "
     "C-D-O6), got 'open'"),
    ("catalogue: six-bar branch misspelt", _HEAD + '[catalogue]\nkind = "stephenson6"\n'
     'branch = ["open", "crossd"]\n',
     "fb.toml: catalogue.branch[1]: expected one of 'open', 'crossed', got 'crossd' (did you mean "
     "'crossed'?)"),
    ("catalogue: a length of 3e300", _HEAD + '[catalogue]\nkind = "fourbar"\nground = 3e300\ncrank = 100\n'
     'coupler = 300\nrocker = 250\n',
     # 3e300 mm squared overflows a float: lengths are refused outside 1e-9 ... 1e9 m
     "fb.toml: catalogue.ground: expected a length from 1e-06 mm to 1e+12 mm, got 3e+300 mm"),
    ("catalogue: a length of 1e-300", _HEAD + '[catalogue]\nkind = "fourbar"\nground = 300\ncrank = 1e-300\n'
     'coupler = 300\nrocker = 250\n',
     "fb.toml: catalogue.crank: expected a length from 1e-06 mm to 1e+12 mm, got 1e-300 mm"),
    ("a 5000-digit coordinate", _replace('A = [0, 100]', 'A = [0, ' + '9' * 5000 + ']'),
     "fb.toml: line 10, column 9: a number of more than 4300 digits; no value needs so many, write "
     "it with an exponent (1.5e3) or fix it"),
    ("a coordinate out of scale", _replace('A = [0, 100]', 'A = [0, 1e300]'),
     "fb.toml: points.A: expected at most 1e+09 m in size, got [0, 1e+300] mm"),
    ("a link length out of scale", _replace('length = 100', 'length = 1e300'),
     "fb.toml: links[1].length: expected a length from 1e-09 m to 1e+09 m, got 1e+300 mm"),
    ("a speed whose square overflows", _replace('speed = 600', 'speed = 1e300'),
     "fb.toml: inputs[0].speed: expected at most 1e+100 rad/s in size (accelerations take its "
     "square), got 1e+300 deg/s"),
    ("a range of more than 1000 turns", _replace('range = [0, 360]', 'range = [0, 360001]'),
     "fb.toml: inputs[0].range: expected angles within 1000 turns of 0 either way, got [0, 360001] deg"),
    ("a transmission angle of one link", BASE + '\n[outputs]\ntransmission = ["coupler", "coupler"]\n',
     "fb.toml: outputs.transmission[0]: expected two different links (a coupler and an output), "
     "got 'coupler' twice"),
    ("a name with a newline", _replace('points = ["A", "B"]', 'points = ["A", "B\\nC"]'),
     "fb.toml: links[2].points[1]: expected a name of printable characters, got 'B\\nC'"),
    ("a name with an escape sequence", _replace('point = "O4"', 'point = "\\u001b[2JO4"\nname = "jO4"'),
     "fb.toml: joints[3].point: expected a name of printable characters, got '\\x1b[2JO4'"),
    ("a name with a tab and NUL", _replace('name = "fb"', 'name = "f\\tb\\u0000"'),
     "fb.toml: name: expected a non-empty text of printable characters, got 'f\\tb\\x00'"),
    ("a long unknown name", _replace('points = ["A", "B"]', 'points = ["A", "' + 'Q' * 200 + '"]'),
     "fb.toml: links[2].points[1]: expected a declared point, got '" + "Q" * 57 + "\u2026'; "
     "declared points are 'O2', 'A', 'B', 'O4'"),
    ("a name of pages", _replace('points = ["A", "B"]', 'points = ["A", "' + 'Q' * 10_000 + '"]'),
     "fb.toml: links[2].points[1]: expected a name of at most 200 characters, got 10,000; "
     "shorten it"),
    ("an unknown name among many", _replace('O4 = [300, 0]', 'O4 = [300, 0]\n'
                                            + "".join(f"X{i} = [{i}, 500]\n" for i in range(100)))
     .replace('points = ["A", "B"]', 'points = ["A", "Q"]'),
     "fb.toml: links[2].points[1]: expected a declared point, got 'Q'; declared points are 'O2', "
     "'A', 'B', 'O4', " + ", ".join(f"'X{i}'" for i in range(16)) + " and 84 more"),
    ("catalogue disagrees with the sketch", BASE + '\n[catalogue]\n'
     + _FOURBAR.replace("coupler = 300", "coupler = 310") + 'rocker = 250\n',
     "fb.toml: catalogue: the sketch does not match fourbar: link 'coupler' has A-B = 300 mm in "
     "the sketch but 310 mm from the parameters; fix the points or the parameters, or delete "
     "[catalogue]"),
]


# The same model in JSON, and what only a JSON file can hold (TOML refuses a key given twice,
# a lone surrogate and a 400-deep nesting itself).
_BASE_JSON = json.dumps(tomllib.loads(BASE))


def _json(old: str, new: str) -> str:
    assert old in _BASE_JSON, old
    return _BASE_JSON.replace(old, new, 1)


JSON_CASES = [
    ("a 5000-digit coordinate", _json('"A": [0, 100]', '"A": [0, ' + "9" * 5000 + "]"),
     "fb.json: line 1, column 106: a number of more than 4300 digits; no value needs so many, "
     "write it with an exponent (1.5e3) or fix it"),
    # 400 levels of lists are read by json, but no message may recurse through them
    ("a name nested 400 deep", _json('"name": "fb"', '"name": ' + "[" * 400 + "]" * 400),
     "fb.json: name" + "[0]" * 31 + ": nested more than 32 deep; no file kinelab reads needs that "
     "many levels"),
    ("a lone surrogate in a name", _json('["A", "B"]', '["A", "\\ud800"]'),
     "fb.json: links[2].points[1]: a lone UTF-16 surrogate in '\\ud800', which is not text; fix "
     "the escape (\\ud800 ... \\udfff) there"),
    ("a lone surrogate as the model's name", _json('"name": "fb"', '"name": "\\udfff"'),
     "fb.json: name: a lone UTF-16 surrogate in '\\udfff', which is not text; fix the escape "
     "(\\ud800 ... \\udfff) there"),
    ("a name with control characters", _json('["A", "B"]', '["A", "B\\n\\t\\u001b[31m\\u0000"]'),
     "fb.json: links[2].points[1]: expected a name of printable characters, got "
     "'B\\n\\t\\x1b[31m\\x00'"),
    ("a key twice", _json('"name": "crank"', '"name": "crank", "name": "arm"'),
     "fb.json: links[1].name: given twice in the same table; keep one"),
    ("a top-level key twice", _json('"schema": 1', '"schema": 1, "schema": 1'),
     "fb.json: schema: given twice in the same table; keep one"),
]
