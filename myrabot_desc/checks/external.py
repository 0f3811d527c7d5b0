"""Codes produced outside the rule functions: by the build (X), by the URDF reader (T010), or for a
file that cannot be processed at all (X000). Each keeps its doc and example here, like the rules.

``EXTERNAL`` (code -> (name, severity, summary)) is what the reports list; ``EXTERNAL_RULES`` has
the whole entry.
"""

from myrabot_desc.checks.rule import Example
from myrabot_desc.records import Struct


class ExternalRule(Struct):
    code: str
    name: str
    severity: str
    summary: str
    why: str
    fix: str
    example: Example


_ROBOT = '<?xml version="1.0"?>\n<robot name="example" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'

EXTERNAL_RULES: dict[str, ExternalRule] = {r.code: r for r in (
    ExternalRule(
        "X000", "input-unprocessable", "error", "The file could not be processed (exit code 2).",
        "The input could not be processed at all (bad XML, missing file, not a `<robot>`): one line "
        "`file:line: error: ...`, exit code 2; the other files of the call are still checked.",
        "Fix the line named in the message.",
        Example(_ROBOT + '  <link name="base_link">\n</robot>\n',
                "robot.urdf:4: error: malformed XML: Opening and ending tag mismatch: link line 3 and robot",
                _ROBOT + '  <link name="base_link"/>\n</robot>\n')),
    ExternalRule(
        "X001", "legacy-upgraded", "warning", "Electric/Fuerte xacro syntax was upgraded during the build.",
        "The build upgraded ROS Electric/Fuerte syntax (un-prefixed `<macro>`, `<include>`, `<property>`, "
        "`<insert_block>`, bare macro calls). Modern xacro would copy these tags into the URDF unexpanded, "
        "so the file only works with this tool or an old ROS.",
        "Write `xacro:` prefixes (the build output shows the modern form).",
        Example(_ROBOT + '  <link name="base_link"/>\n  <macro name="caster" params="name">\n'
                '    <link name="${name}"/>\n  </macro>\n  <xacro:caster name="caster_link"/>\n'
                '  <joint name="caster_joint" type="fixed">\n    <parent link="base_link"/>\n'
                '    <child link="caster_link"/>\n  </joint>\n</robot>\n',
                "legacy <macro> upgraded to <xacro:macro>; xacro 2.x would copy it into the URDF unexpanded",
                _ROBOT + '  <link name="base_link"/>\n  <xacro:macro name="caster" params="name">\n'
                '    <link name="${name}"/>\n  </xacro:macro>\n  <xacro:caster name="caster_link"/>\n'
                '  <joint name="caster_joint" type="fixed">\n    <parent link="base_link"/>\n'
                '    <child link="caster_link"/>\n  </joint>\n</robot>\n',
                filename="robot.urdf.xacro")),
    ExternalRule(
        "X002", "unexpanded-macro-call", "error",
        "A tag looks like a macro call that xacro passed through unexpanded.",
        "A tag in the URDF looks like a macro call that was never expanded (for example because the file "
        "defining the macro is not included). URDF parsers ignore the tag, so everything the macro would "
        "have added is silently missing (the seed's five sonars).",
        "Include the file that defines the macro and call it as `<xacro:NAME>`.",
        Example(_ROBOT + '  <link name="base_link"/>\n  <sonar id="1" parent="base_link"/>\n</robot>\n',
                "<sonar> looks like a call of macro 'sonar' (defined in sonar.xacro), but it was not expanded: "
                "the file defining it is not included, so everything it would add is missing",
                _ROBOT + '  <xacro:include filename="sonar.xacro"/>\n  <link name="base_link"/>\n'
                '  <xacro:sonar id="1" parent="base_link"/>\n</robot>\n',
                filename="robot.urdf.xacro",
                files={"sonar.xacro": _ROBOT + '  <xacro:macro name="sonar" params="id parent">\n'
                       '    <link name="sonar_${id}_link"/>\n    <joint name="sonar_${id}_joint" type="fixed">\n'
                       '      <parent link="${parent}"/>\n      <child link="sonar_${id}_link"/>\n'
                       '    </joint>\n  </xacro:macro>\n</robot>\n'},
                note="sonar.xacro defines the macro sonar (a link and a fixed joint).")),
    ExternalRule(
        "X003", "macro-only-file", "warning",
        "The top-level file defines macros but instantiates none (empty robot).",
        "The file given defines macros and instantiates none, so the robot is empty (xarm_ros #196, "
        "universal_robot #482).",
        "Check the top-level assembly, or include this file from one.",
        Example(_ROBOT + '  <xacro:macro name="wheel" params="side">\n    <link name="${side}_wheel"/>\n'
                '  </xacro:macro>\n</robot>\n',
                "this file defines 1 macro(s) (wheel) and instantiates none: the URDF has no links",
                _ROBOT + '  <xacro:macro name="wheel" params="side">\n    <link name="${side}_wheel"/>\n'
                '  </xacro:macro>\n  <xacro:wheel side="left"/>\n</robot>\n',
                filename="robot.urdf.xacro")),
    ExternalRule(
        "X004", "package-resolves", "warning", "A package:// URI names a package that cannot be found.",
        "A `package://NAME/...` URI names a package no search path provides; meshes and textures under it "
        "cannot be found.",
        "Pass `-p NAME=PATH` or `--package-path DIR`, or correct the package name.",
        Example(_ROBOT + '  <link name="base_link">\n    <visual><geometry>\n'
                '      <mesh filename="package://missing_pkg/meshes/base.stl"/>\n    </geometry></visual>\n'
                '  </link>\n</robot>\n',
                "package 'missing_pkg' of package://missing_pkg/meshes/base.stl cannot be found "
                "(give -p missing_pkg=PATH or --package-path)",
                _ROBOT + '  <link name="base_link">\n    <visual><geometry>\n'
                '      <box size="0.3 0.2 0.1"/>\n    </geometry></visual>\n  </link>\n</robot>\n',
                filename="robot.urdf.xacro")),
    ExternalRule(
        "X005", "expression-refused", "error", "A ${} expression was refused by the safe evaluator.",
        "A `${}` expression uses something outside the safe evaluator's allow-list (dunder names and "
        "attributes, imports, file or process access); model files are untrusted input in CI.",
        "Rewrite the expression with arithmetic and the allowed functions, or pass `--unsafe-eval` for "
        "a trusted file.",
        Example(_ROBOT + '  <xacro:property name="x" value="${__import__(\'os\').getcwd()}"/>\n'
                '  <link name="base_${x}"/>\n</robot>\n',
                "refused expression ${__import__('os').getcwd()}: name '__import__' is not allowed "
                "(--unsafe-eval allows it for trusted files)",
                _ROBOT + '  <xacro:property name="x" value="${0.1 * 2}"/>\n  <link name="base_${x}"/>\n</robot>\n',
                filename="robot.urdf.xacro")),
    ExternalRule(
        "X006", "path-outside-allowed", "error", "An include or load_yaml reaches outside the allowed folders.",
        "An include or `load_yaml` points outside the input's folder and the resolved packages.",
        "Pass `--allow-path DIR`, or move the file into the package.",
        Example(_ROBOT + '  <xacro:include filename="../parts.xacro"/>\n  <link name="base_link"/>\n</robot>\n',
                "refusing to read robot/../parts.xacro: outside the input's folder and the package roots "
                "(use --allow-path DIR to allow it)",
                _ROBOT + '  <xacro:include filename="parts.xacro"/>\n  <link name="base_link"/>\n</robot>\n',
                filename="robot/robot.urdf.xacro",
                files={"parts.xacro": _ROBOT + "</robot>\n", "robot/parts.xacro": _ROBOT + "</robot>\n"},
                note="parts.xacro exists both next to the model and one folder up.")),
    ExternalRule(
        "X007", "environment-dependent", "info",
        "The build read $(env VAR)/$(optenv VAR): its output depends on the environment (variables listed).",
        "A model that reads `$(env VAR)` or `$(optenv VAR default)` builds differently on each machine "
        "and CI runner. The finding lists each variable: \"(set)\" when the environment gave it (its value "
        "is never printed: a model could otherwise print a CI secret into a report or a log; "
        "MYRABOT_DESC_SHOW_ENV_VALUES=1 shows it), the default when `$(optenv)` fell back to it; past "
        "eight variables it counts them and names eight set and eight unset ones, and the JSON output's "
        "`data.environment` has them all (null for a set one).",
        "Pin the values: make them xacro args (`NAME:=VALUE`, or `args` in the configuration) or set "
        "them in the CI job; `--no-env` refuses the lookups.",
        Example(_ROBOT + '  <link name="$(optenv MYRABOT_EXAMPLE_BASE base_link)"/>\n</robot>\n',
                "the build depends on the environment: MYRABOT_EXAMPLE_BASE='base_link' (unset: default); "
                "pin them as xacro args or in the CI job",
                _ROBOT + '  <xacro:arg name="base" default="base_link"/>\n  <link name="$(arg base)"/>\n</robot>\n',
                filename="robot.urdf.xacro",
                note="MYRABOT_EXAMPLE_BASE is not set.")),
    ExternalRule(
        "X009", "unused-suppression", "warning",
        "A myrabot-desc: ignore[...] comment silenced nothing (or names an unknown code).",
        "An inline suppression (`<!-- myrabot-desc: ignore[CODES] why -->`) that silenced no finding "
        "in the whole run, for a code the run checked, hides the next real problem of that element; "
        "one naming a code that does not exist silences nothing at all (like ruff's RUF100).",
        "Remove the comment, or correct the code.",
        Example(_ROBOT + '  <!-- myrabot-desc: ignore[I008] light on purpose -->\n  <link name="base_link"/>\n'
                '</robot>\n',
                "unused suppression ignore[I008]: no I008 finding here in this run; remove it",
                _ROBOT + '  <link name="base_link"/>\n</robot>\n',
                filename="robot.urdf.xacro")),
    ExternalRule(
        "X008", "xacro-warning", "warning", "xacro itself warned while expanding the file.",
        "xacro prints warnings for things it ignores (an unknown attribute on a xacro tag, a redefined "
        "global property, child elements of an include); the result may differ from what was meant.",
        "Do what xacro's message says (the attribute is ignored: remove it or spell it as xacro reads it).",
        Example(_ROBOT + '  <xacro:property name="wheel_radius" value="0.05" unit="m"/>\n'
                '  <link name="base_link"/>\n</robot>\n',
                "xacro: xacro:property: unknown attribute(s): unit",
                _ROBOT + '  <xacro:property name="wheel_radius" value="0.05"/>  <!-- m -->\n'
                '  <link name="base_link"/>\n</robot>\n',
                filename="robot.urdf.xacro")),
    ExternalRule(
        "T010", "value-parses", "error",
        "A number or vector in the URDF cannot be read (the reader used the default).",
        "A value the URDF reader needs (a mass, a vector, a limit) is not a number; the reader used the "
        "default, so the model differs from what was meant.",
        "Write a plain decimal number (`0.5`, not `0,5`).",
        Example('<link name="arm">\n  <inertial>\n    <mass value="0,5"/>\n'
                '    <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>\n  </inertial>\n'
                '</link>\n<joint name="arm_joint" type="fixed">\n  <parent link="base_link"/>\n'
                '  <child link="arm"/>\n</joint>',
                '<mass value="0,5">: not a number',
                '<link name="arm">\n  <inertial>\n    <mass value="0.5"/>\n'
                '    <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>\n  </inertial>\n'
                '</link>\n<joint name="arm_joint" type="fixed">\n  <parent link="base_link"/>\n'
                '  <child link="arm"/>\n</joint>')),
)}

EXTERNAL: dict[str, tuple[str, str, str]] = {c: (r.name, r.severity, r.summary) for c, r in EXTERNAL_RULES.items()}
