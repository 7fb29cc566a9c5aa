"""Writes, as C++, the Pinocchio models that `buildModelFromUrdf` reads from the
robots in `robots/`: one function per robot adding the same joints (type,
axis, placement) and bodies (mass, centre of mass, inertia) with every number
printed to 17 digits, and the tool frame (an operational frame on its joint at
the file's placement). The PyPI wheel `pin` ships the URDF parser's library
but not urdfdom's headers, so `urdf.cpp` builds the models this way. `ROBOTS`
lists each model's function, its arm's coordinates (the Panda's fingers are
not) and its tool frame; `FLOATING` the same for robots on a free-flyer
root (Solo 12), read with `pin.JointModelFreeFlyer()` as their root.

    python3 urdf_model.py ROBOTS_DIR OUT.hpp
"""
import sys
import pinocchio as pin


def vec(v):
    return ", ".join(repr(float(x)) for x in v)


def mat(m):
    return ", ".join(repr(float(m[i, j])) for i in range(3) for j in range(3))


def joint(j):
    name = j.shortname()
    simple = {"JointModelRX", "JointModelRY", "JointModelRZ", "JointModelPX", "JointModelPY", "JointModelPZ",
              "JointModelRUBX", "JointModelRUBY", "JointModelRUBZ"}
    if name in simple:
        return f"pin::{name}()"
    if name == "JointModelFreeFlyer":
        return "pin::JointModelFreeFlyer()"
    if name in ("JointModelRevoluteUnaligned", "JointModelPrismaticUnaligned"):
        return f"pin::{name}(Eigen::Vector3d({vec(j.extract().axis)}))"
    raise SystemExit(f"joint type {name} not written")


def model_function(fn, model, frame):
    out = [f"static pin::Model {fn}() {{", "  pin::Model model;", f'  model.name = "{model.name}";']
    for i in range(1, model.njoints):
        p = model.jointPlacements[i]
        inertia = model.inertias[i]
        out.append(
            f"  {{ Eigen::Matrix3d R; R << {mat(p.rotation)};\n"
            f"    pin::JointIndex j = model.addJoint({model.parents[i]}, {joint(model.joints[i])}, "
            f'pin::SE3(R, Eigen::Vector3d({vec(p.translation)})), "{model.names[i]}");\n'
            f"    Eigen::Matrix3d I; I << {mat(inertia.inertia)};\n"
            f"    model.appendBodyToJoint(j, pin::Inertia({float(inertia.mass)!r}, "
            f"Eigen::Vector3d({vec(inertia.lever)}), I)); }}"
        )
    f = model.frames[model.getFrameId(frame, pin.BODY)]
    p = f.placement
    out.append(
        f"  {{ Eigen::Matrix3d R; R << {mat(p.rotation)};\n"
        f'    model.addFrame(pin::Frame("{frame}", {f.parentJoint}, '
        f"pin::SE3(R, Eigen::Vector3d({vec(p.translation)})), pin::OP_FRAME), false); }}"
    )
    out += ["  return model;", "}"]
    return "\n".join(out)


# function, file, the arm's coordinates, the tool frame (as urdf_reference.py)
ROBOTS = [
    ("ur5", "ur5.urdf", 6, "tool0"),
    ("panda", "panda.urdf", 7, "panda_hand"),
    ("ur10", "ur10.urdf", 6, "tool0"),
    ("kinova", "kinova.urdf", 6, "j2s6s200_end_effector"),
    ("z1", "z1.urdf", 7, "gripperStator"),
    ("xarm7", "xarm7.urdf", 7, "link_eef"),
]
# The same for robots on a free-flyer root (their `arm`: the joints after it).
FLOATING = [
    ("solo12", "solo12.urdf", 12, "FL_FOOT"),
]

robots, target = sys.argv[1], sys.argv[2]
with open(target, "w") as f:
    f.write("// Written by urdf_model.py from the URDF files in robots/.\n")
    for fn, file, _, frame in ROBOTS:
        f.write(model_function(fn, pin.buildModelFromUrdf(f"{robots}/{file}"), frame) + "\n\n")
    for fn, file, _, frame in FLOATING:
        model = pin.buildModelFromUrdf(f"{robots}/{file}", pin.JointModelFreeFlyer())
        f.write(model_function(fn, model, frame) + "\n\n")
    f.write("struct Robot { const char* name; pin::Model (*build)(); int arm; const char* tool; };\n")
    for table, robots_of in (("ROBOTS", ROBOTS), ("FLOATING", FLOATING)):
        rows = ",\n".join(f'  {{"{fn}", {fn}, {arm}, "{frame}"}}' for fn, _, arm, frame in robots_of)
        f.write(f"static const Robot {table}[] = {{\n{rows}}};\n")
