#!/usr/bin/python3
"""Every #include between the layers of src/grainflow/ goes down the graph CMakeLists.txt declares
(grainflow_layer(NAME DEPENDS ...)), header-only includes too, which a link would not catch; the
graph has no cycle; and every folder under src/grainflow/ is a declared layer. Two rules hold beyond
the graph, so that a new DEPENDS cannot quietly undo them: the engines reach none of the layers that
bring HDF5 and FFTW (observe, io, analysis), and app/ includes only app/, run/ and core/ headers.

Usage: /usr/bin/python3 tests/architecture/test_layers.py [REPOSITORY_ROOT]
Exit status 0 when the layering holds, 1 with every violation listed.
"""
import os
import re
import sys


def declared_layers(cmake_text):
    """{layer: set of direct dependencies} from the grainflow_layer(...) calls."""
    layers = {}
    for call in re.finditer(r"^\s*grainflow_layer\(([^)]*)\)", cmake_text, re.MULTILINE):
        words = call.group(1).split()
        name, deps, section = words[0], set(), None
        for word in words[1:]:
            if word in ("DEPENDS", "PACKAGES", "SOURCES"):
                section = word
            elif section == "DEPENDS":
                deps.add(word)
        layers.setdefault(name, set()).update(deps)
    return layers


# Layers an engine must not reach: the observers and the file and post-processing layers under them.
ENGINE_FORBIDDEN = {"dem": {"observe", "io", "analysis"}, "edmd": {"observe", "io", "analysis"}}
# The program's own folder hands every subcommand's work to run/; core/ gives it the errors and version.
APP_INCLUDES = {"app", "run", "core"}


def reachable(layers, start):
    seen, stack = set(), list(layers.get(start, ()))
    while stack:
        layer = stack.pop()
        if layer not in seen:
            seen.add(layer)
            stack.extend(layers.get(layer, ()))
    return seen


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    with open(os.path.join(root, "CMakeLists.txt")) as f:
        layers = declared_layers(f.read())
    problems = []
    if len(layers) < 5:
        problems.append(f"only {len(layers)} grainflow_layer() calls found in CMakeLists.txt")
    for layer in layers:
        for dep in layers[layer]:
            if dep not in layers:
                problems.append(f"layer {layer} depends on undeclared layer {dep}")
        if layer in reachable(layers, layer):
            problems.append(f"layer {layer} depends on itself through {sorted(layers[layer])}")
    for engine, forbidden in ENGINE_FORBIDDEN.items():
        if engine not in layers:
            problems.append(f"engine layer {engine} is not declared in CMakeLists.txt")
        for layer in sorted(reachable(layers, engine) & forbidden):
            problems.append(f"engine layer {engine} depends on {layer}: an engine may not reach {sorted(forbidden)}")
    source_root = os.path.join(root, "src", "grainflow")
    include = re.compile(r'^\s*#\s*include\s+"grainflow/([a-z_]+)/([^"]+)"', re.MULTILINE)
    checked = 0
    for layer in sorted(os.listdir(source_root)):
        folder = os.path.join(source_root, layer)
        if not os.path.isdir(folder):
            continue
        if layer not in layers:
            problems.append(f"src/grainflow/{layer}/ is not a layer declared in CMakeLists.txt")
            continue
        allowed = reachable(layers, layer) | {layer}
        if layer == "app":
            allowed &= APP_INCLUDES
        for name in sorted(os.listdir(folder)):
            if not re.search(r"\.(hpp|cpp|in)$", name):
                continue
            with open(os.path.join(folder, name)) as f:
                text = f.read()
            for match in include.finditer(text):
                checked += 1
                if match.group(1) not in allowed:
                    problems.append(f"src/grainflow/{layer}/{name} includes grainflow/{match.group(1)}/{match.group(2)}: "
                                    f"{layer} may use only {sorted(allowed)}")
    if checked < 100:
        problems.append(f"only {checked} includes between grainflow files were found; is this the repository?")
    for p in problems:
        print(p)
    print(f"test_layers: {len(layers)} layers, {checked} includes checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
