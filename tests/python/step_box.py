"""An AP214 STEP file of the box [0, a] x [0, b] x [0, c] as a B-rep solid (six PLANE faces bounded by LINE
edges), written from the ISO 10303-42 topology entities, so the import is tested on a solid whose volume is
a b c."""


def box_step(a, b, c):
    corner = {(i, j, k): (i * a, j * b, k * c) for i in (0, 1) for j in (0, 1) for k in (0, 1)}
    faces = [  # corners counter-clockwise seen from outside, the outward normal
        ([(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)], (0, 0, -1)),
        ([(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)], (0, 0, 1)),
        ([(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)], (0, -1, 0)),
        ([(0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0)], (0, 1, 0)),
        ([(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)], (-1, 0, 0)),
        ([(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)], (1, 0, 0)),
    ]
    lines = []
    ids = iter(range(100, 10**6))

    def add(text):
        n = next(ids)
        lines.append(f"#{n}={text};")
        return n

    def f(x):
        return f"{float(x):.17g}" if "." in f"{float(x):.17g}" else f"{float(x):.1f}"

    point = {key: add(f"CARTESIAN_POINT('',({f(p[0])},{f(p[1])},{f(p[2])}))") for key, p in corner.items()}
    vertex = {key: add(f"VERTEX_POINT('',#{point[key]})") for key in corner}
    edges = {}
    for quad, _ in faces:
        for s, e in zip(quad, quad[1:] + quad[:1]):
            if (s, e) in edges or (e, s) in edges:
                continue
            d = [corner[e][k] - corner[s][k] for k in range(3)]
            length = sum(x * x for x in d) ** 0.5
            direction = add(f"DIRECTION('',({f(d[0] / length)},{f(d[1] / length)},{f(d[2] / length)}))")
            vector = add(f"VECTOR('',#{direction},{f(length)})")
            line = add(f"LINE('',#{point[s]},#{vector})")
            edges[(s, e)] = add(f"EDGE_CURVE('',#{vertex[s]},#{vertex[e]},#{line},.T.)")
    face_ids = []
    for quad, normal in faces:
        oriented = []
        for s, e in zip(quad, quad[1:] + quad[:1]):
            if (s, e) in edges:
                oriented.append(add(f"ORIENTED_EDGE('',*,*,#{edges[(s, e)]},.T.)"))
            else:
                oriented.append(add(f"ORIENTED_EDGE('',*,*,#{edges[(e, s)]},.F.)"))
        loop = add("EDGE_LOOP('',(" + ",".join(f"#{o}" for o in oriented) + "))")
        bound = add(f"FACE_OUTER_BOUND('',#{loop},.T.)")
        p0, p1 = corner[quad[0]], corner[quad[1]]
        ref = [p1[k] - p0[k] for k in range(3)]
        ref_len = sum(x * x for x in ref) ** 0.5
        axis = add(f"DIRECTION('',({f(normal[0])},{f(normal[1])},{f(normal[2])}))")
        refdir = add(f"DIRECTION('',({f(ref[0] / ref_len)},{f(ref[1] / ref_len)},{f(ref[2] / ref_len)}))")
        placement = add(f"AXIS2_PLACEMENT_3D('',#{point[quad[0]]},#{axis},#{refdir})")
        plane = add(f"PLANE('',#{placement})")
        face_ids.append(add(f"ADVANCED_FACE('',(#{bound}),#{plane},.T.)"))
    shell = add("CLOSED_SHELL('',(" + ",".join(f"#{x}" for x in face_ids) + "))")
    solid = add(f"MANIFOLD_SOLID_BREP('box',#{shell})")
    head = """ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('box'),'2;1');
FILE_NAME('box.stp','2026-11-25T00:00:00',(''),(''),'','','');
FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 3 1 1 }'));
ENDSEC;
DATA;
#1=APPLICATION_CONTEXT('core data for automotive mechanical design processes');
#2=APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#1);
#3=PRODUCT_CONTEXT('',#1,'mechanical');
#4=PRODUCT('box','box','',(#3));
#6=PRODUCT_DEFINITION_FORMATION('','',#4);
#7=PRODUCT_DEFINITION_CONTEXT('part definition',#1,'design');
#8=PRODUCT_DEFINITION('design','',#6,#7);
#9=PRODUCT_DEFINITION_SHAPE('','',#8);
#10=SHAPE_DEFINITION_REPRESENTATION(#9,#11);
#12=AXIS2_PLACEMENT_3D('',#13,#14,#15);
#13=CARTESIAN_POINT('',(0.,0.,0.));
#14=DIRECTION('',(0.,0.,1.));
#15=DIRECTION('',(1.,0.,0.));
#90=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#94))
  GLOBAL_UNIT_ASSIGNED_CONTEXT((#91,#92,#93))REPRESENTATION_CONTEXT('Context #1','3D Context'));
#91=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));
#92=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));
#93=(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT());
#94=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#91,'distance_accuracy_value','confusion accuracy');
"""
    rep = f"#11=ADVANCED_BREP_SHAPE_REPRESENTATION('box',(#12,#{solid}),#90);"
    return head + rep + "\n" + "\n".join(lines) + "\nENDSEC;\nEND-ISO-10303-21;\n"
