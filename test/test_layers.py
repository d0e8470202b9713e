"""The package folders and docs/architecture.md's picture of the layers agree: the picture draws every
top-level folder that holds a package, top to bottom, and no package depends on (package.xml),
includes (C++) or imports (Python) a package of a folder drawn above its own."""

import re
import xml.etree.ElementTree as ET

from support import REPO

PICTURE = REPO / "docs" / "architecture.md"
DEPENDENCY_TAGS = ("depend", "build_depend", "exec_depend", "run_depend", "build_export_depend", "test_depend")
# Python modules whose package has another name
MODULE_PACKAGES = {"rotors_sim": "rotors_python"}


def drawn_layers() -> list[str]:
    """The folders of the picture under '## The layers', top to bottom."""
    text = PICTURE.read_text()
    block = text.split("## The layers", 1)[1].split("```", 2)[1]
    return re.findall(r"^ (\w+)/ ", block, flags=re.MULTILINE)


def manifests():
    """(package.xml, its top-level folder) of the catkin packages: the tests' own packages, the
    repository's root metapackage and the ROS 2 interface packages (ament_cmake, built apart by
    scripts/setup_ros2.sh; the same names as their ROS 1 packages) left out."""
    for xml in sorted(REPO.rglob("package.xml")):
        parts = xml.relative_to(REPO).parts
        if parts[0] in ("build", "test") or len(parts) == 1 or ET.parse(xml).getroot().findtext("export/build_type") == "ament_cmake":
            continue
        yield xml, parts[0]


def packages() -> dict[str, str]:
    """Package name -> the top-level folder that holds it."""
    return {ET.parse(xml).getroot().findtext("name"): folder for xml, folder in manifests()}


def test_the_picture_draws_every_package_folder_once():
    layers = drawn_layers()
    assert len(layers) == len(set(layers)), layers
    assert set(layers) == set(packages().values())


def test_no_package_reaches_a_layer_drawn_above_it():
    layer = {folder: i for i, folder in enumerate(drawn_layers())}
    folder_of = packages()
    upward = []

    def check(where: str, own_folder: str, used: str) -> None:
        used = MODULE_PACKAGES.get(used, used)
        if used in folder_of and layer[folder_of[used]] < layer[own_folder]:
            upward.append(f"{where} uses {used} ({folder_of[used]}/, drawn above {own_folder}/)")

    for xml, folder in manifests():
        for tag in DEPENDENCY_TAGS:
            for dep in ET.parse(xml).getroot().iter(tag):
                check(str(xml.relative_to(REPO)), folder, dep.text.strip())
    for folder in layer:
        for path in (REPO / folder).rglob("*"):
            if not path.is_file():
                continue
            if path.suffix in (".h", ".hpp", ".cpp", ".cc"):
                for used in re.findall(r'^#include [<"](\w+)/', path.read_text(errors="replace"), flags=re.MULTILINE):
                    check(str(path.relative_to(REPO)), folder, used)
            elif path.suffix == ".py" or (path.parent.name == "scripts" and path.read_bytes()[:2] == b"#!"):
                text = path.read_text(errors="replace")
                for used in re.findall(r"^\s*(?:from|import) (\w+)", text, flags=re.MULTILINE):
                    check(str(path.relative_to(REPO)), folder, used)
    print(f"{len(layer)} layers, {len(folder_of)} packages: {len(upward)} upward")
    assert not upward, "\n".join(upward)
