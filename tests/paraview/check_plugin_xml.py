"""Static checks of the plugin's server-manager XML against the C++ headers.

    pvpython check_plugin_xml.py --xml BUILD/paraview-plugin/PointSetSurfaces.xml --filters SRC/filters

Fails (exit status 1, one line per problem) when
- a proxy lacks a Documentation element with short_help, long_help and text, or a property
  lacks one with short_help and text (the tooltip and the help panel);
- a filter or source proxy is not in the "Point Set Surfaces" menu category (readers excepted:
  File > Open lists them);
- a property named X does not call SetX;
- a property's default_values differ from the initial value of the C++ member it sets (read from
  the class's header and its superclasses' headers in filters/; a string's from the
  this->SetX("...") of its constructor), or the member cannot be found;
- a range or enumeration domain allows values that the C++ setter's vtkSetClampMacro clamps away;
- a class of the VTK module has no proxy (vtkPointSetSurfaceImplicitFunction excepted: it is not a
  pipeline object, see docs/paraview.md; nor the abstract vtkPointSetSurfaceAlgorithm), or the surface sub-proxy does not expose every
  property of the PointSetSurface proxy;
- a filter whose class (or superclass) says it runs distributed (SupportsDistributedRun() returning
  true) is still multiprocess_support="single_process", or a single_process filter does not say
  why in its documentation ("Single process only ...").
Plain Python (no ParaView needed); run with pvpython so ctest needs nothing else.
"""
import argparse
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

MENU_CATEGORY = "Point Set Surfaces"
# Classes of the module that are deliberately not proxies (with the reason).
NOT_PROXIES = {
    # A vtkImplicitFunction whose cloud is set by SetInputData(vtkPointSet*): ParaView's implicit
    # function proxies are not pipeline objects and cannot receive a pipeline output. The plugin
    # exposes g through the field sampler's ImplicitG array instead.
    "vtkPointSetSurfaceImplicitFunction",
    # The abstract base of the polydata filters (no New()): its properties are its subclasses'.
    "vtkPointSetSurfaceAlgorithm",
}
SYMBOLS = {
    "VTK_ID_MAX": float(2**63 - 1),
    "VTK_INT_MAX": float(2**31 - 1),
    "VTK_DOUBLE_MAX": sys.float_info.max,
    "true": 1.0,
    "false": 0.0,
}


class Header:
    """What the checks need from one filters/*.h: members' initial values, clamps, enums, base."""

    def __init__(self, path):
        text = open(path, encoding="utf-8").read()
        # String members (vtkSetStringMacro) get their initial value in the constructor.
        source = os.path.splitext(path)[0] + ".cxx"
        self.strings = {}
        if os.path.exists(source):
            self.strings = dict(re.findall(r'this->Set(\w+)\("([^"]*)"\);', open(source, encoding="utf-8").read()))
        # Drop comments so documentation examples are not read as code.
        text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
        text = re.sub(r"//[^\n]*", "", text)
        self.enums = {}
        for body in re.findall(r"enum\s+\w+\s*\{([^}]*)\}", text):
            for name, value in re.findall(r"(\w+)\s*=\s*(-?\d+)", body):
                self.enums[name] = float(value)
        # Named values outside enums, e.g. static constexpr double BORDER_OFFSET_AUTOMATIC = -1.0;
        for name, value in re.findall(r"static\s+constexpr\s+(?:double|int)\s+(\w+)\s*=\s*(-?[\d.]+)\s*;", text):
            self.enums[name] = float(value)
        self.members = {}
        for _type, name, is_array, value in re.findall(
            r"^\s*(int|double|bool|vtkIdType)\s+(\w+)\s*(\[\s*\d+\s*\])?\s*=\s*([^;]+);", text, flags=re.M
        ):
            value = value.strip()
            if is_array:
                value = value.strip("{} ")
                self.members[name] = [v.strip() for v in value.split(",")]
            else:
                self.members[name] = [value]
        self.clamps = {}
        for name, _type, lo, hi in re.findall(
            r"vtkSetClampMacro\(\s*(\w+)\s*,\s*(\w+)\s*,\s*([^,]+?)\s*,\s*([^)]+?)\s*\)", text
        ):
            self.clamps[name] = (lo, hi)
        distributed = re.search(r"bool\s+SupportsDistributedRun\(\)\s*const[^{]*\{\s*return\s+(true|false)\s*;", text)
        self.distributed = None if distributed is None else distributed.group(1) == "true"
        base = re.search(r"class\s+\w+\s+(\w+)\s*:\s*public\s+(\w+)", text)
        self.base = base.group(2) if base else None


def load_chain(filters_dir, cls):
    """The class's header followed by those of its superclasses that live in filters/."""
    chain = []
    while cls:
        path = os.path.join(filters_dir, cls + ".h")
        if not os.path.exists(path):
            break
        header = Header(path)
        chain.append(header)
        cls = header.base
    return chain


def value_of(token, chain):
    token = token.strip()
    for header in chain:
        if token in header.enums:
            return header.enums[token]
    if token in SYMBOLS:
        return SYMBOLS[token]
    # A power of two written as a shift, e.g. vtkIdType(1) << 24 (MaximumNumberOfBandCells).
    shift = re.fullmatch(r"(?:\w+\(\s*)?(\d+)\s*\)?\s*<<\s*(\d+)", token)
    if shift:
        return float(int(shift.group(1)) << int(shift.group(2)))
    return float(token)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--xml", required=True)
    parser.add_argument("--filters", required=True, help="the filters/ folder with the headers")
    args = parser.parse_args()

    problems = []
    root = ET.parse(args.xml).getroot()
    checked_defaults = 0
    checked_multiprocess = 0

    proxies = {}
    for group in root.findall("ProxyGroup"):
        for proxy in group:
            if proxy.tag not in ("Proxy", "SourceProxy", "WriterProxy"):
                continue
            name = proxy.get("name")
            where = "%s/%s" % (group.get("name"), name)
            proxies[name] = (group.get("name"), proxy)
            doc = proxy.find("Documentation")
            if doc is None or not (doc.get("short_help") or "").strip() or not (doc.get("long_help") or "").strip():
                problems.append("%s: Documentation with short_help and long_help missing" % where)
            if doc is not None and not (doc.text or "").strip():
                problems.append("%s: Documentation has no text" % where)
            # Readers are listed by File > Open (their ReaderFactory hint), not in a menu.
            if group.get("name") in ("filters", "sources") and proxy.find("Hints/ReaderFactory") is None:
                menu = proxy.find("Hints/ShowInMenu")
                if menu is None or menu.get("category") != MENU_CATEGORY:
                    problems.append('%s: not in the "%s" menu category' % (where, MENU_CATEGORY))

            chain = load_chain(args.filters, proxy.get("class"))
            if not chain:
                problems.append("%s: no header for class %s in %s" % (where, proxy.get("class"), args.filters))
                continue
            # The nearest declaration in the chain decides, as C++ overriding does.
            distributed = next((h.distributed for h in chain if h.distributed is not None), False)
            single = proxy.get("multiprocess_support") == "single_process"
            if distributed and single:
                problems.append("%s: runs distributed but is still multiprocess_support=single_process" % where)
            if single and "Single process only" not in ((doc.text or "") if doc is not None else ""):
                problems.append("%s: single_process without the reason in its documentation" % where)
            if single or distributed:
                checked_multiprocess += 1
            for prop in proxy:
                if not prop.tag.endswith("Property"):
                    continue
                pwhere = "%s.%s" % (where, prop.get("name"))
                pdoc = prop.find("Documentation")
                if pdoc is None or not (pdoc.text or "").strip() or not (pdoc.get("short_help") or "").strip():
                    problems.append("%s: Documentation with short_help and text missing" % pwhere)
                if prop.get("panel_visibility") not in (None, "default", "advanced", "never"):
                    problems.append("%s: unknown panel_visibility %s" % (pwhere, prop.get("panel_visibility")))
                # Inputs, and file names, which have no default to compare.
                if prop.tag == "InputProperty" or prop.get("name") == "FileName":
                    continue
                command = prop.get("command") or ""
                if not command.startswith("Set"):
                    problems.append("%s: command %r is not a setter" % (pwhere, command))
                    continue
                member = command[3:]
                if member != prop.get("name"):
                    problems.append("%s: property %s calls %s (expected Set%s)" % (pwhere, prop.get("name"), command, prop.get("name")))
                if prop.tag == "StringVectorProperty":
                    cpp = next((h.strings[member] for h in chain if member in h.strings), None)
                    if cpp is None:
                        problems.append("%s: no this->Set%s(\"...\") in the constructor of %s"
                                        % (pwhere, member, proxy.get("class")))
                    elif prop.get("default_values") != cpp:
                        problems.append("%s: XML default %r, C++ default %r" % (pwhere, prop.get("default_values"), cpp))
                    else:
                        checked_defaults += 1
                    continue
                cpp = next((h.members[member] for h in chain if member in h.members), None)
                if cpp is None:
                    problems.append("%s: no C++ member %s with an initial value in %s" % (pwhere, member, proxy.get("class")))
                    continue
                xml_defaults = (prop.get("default_values") or "").split()
                if not xml_defaults:
                    problems.append("%s: no default_values" % pwhere)
                    continue
                try:
                    want = [value_of(v, chain) for v in cpp]
                    got = [float(v) for v in xml_defaults]
                except ValueError as e:
                    problems.append("%s: cannot compare defaults (%s)" % (pwhere, e))
                    continue
                if len(want) != len(got) or any(
                    not math.isclose(a, b, rel_tol=1e-12, abs_tol=0.0) for a, b in zip(want, got)
                ):
                    problems.append("%s: XML default %s, C++ default %s" % (pwhere, xml_defaults, cpp))
                checked_defaults += 1
                clamp = next((h.clamps[member] for h in chain if member in h.clamps), None)
                if clamp is None:
                    continue
                lo, hi = value_of(clamp[0], chain), value_of(clamp[1], chain)
                for domain in prop:
                    if domain.tag in ("IntRangeDomain", "DoubleRangeDomain"):
                        for key in ("min", "max"):
                            for v in (domain.get(key) or "").split():
                                if not lo <= float(v) <= hi:
                                    problems.append("%s: domain %s %s outside the C++ clamp [%s, %s]" % (pwhere, key, v, clamp[0], clamp[1]))
                    if domain.tag == "EnumerationDomain":
                        for entry in domain.findall("Entry"):
                            if not lo <= float(entry.get("value")) <= hi:
                                problems.append("%s: enumeration value %s outside the C++ clamp" % (pwhere, entry.get("value")))

    # Every class of the module is a proxy (or deliberately not).
    cmake = open(os.path.join(args.filters, "CMakeLists.txt"), encoding="utf-8").read()
    classes = re.search(r"set\(classes(.*?)\)", cmake, flags=re.S).group(1).split()
    exposed_classes = {p.get("class") for _, p in proxies.values()}
    for cls in classes:
        if cls not in exposed_classes and cls not in NOT_PROXIES:
            problems.append("class %s of the VTK module has no proxy" % cls)

    # The surface sub-proxy exposes every property of the surface proxy, in every filter.
    surface = proxies.get("PointSetSurface")
    if surface is None:
        problems.append("no PointSetSurface proxy")
    else:
        surface_props = {p.get("name") for p in surface[1] if p.tag.endswith("Property")}
        for name, (group, proxy) in proxies.items():
            for sub in proxy.findall("SubProxy"):
                exposed = {p.get("name") for p in sub.iter("Property")}
                if exposed != surface_props:
                    problems.append("%s: sub-proxy exposes %s, the surface has %s" % (name, sorted(exposed), sorted(surface_props)))
            if group == "filters" and not proxy.findall("SubProxy"):
                problems.append("%s: no surface sub-proxy" % name)

    print("checked %d proxies, %d defaults against the headers" % (len(proxies), checked_defaults))
    if checked_multiprocess < 5:
        problems.append("only %d filters' multiprocess support checked: the XML or the header parser is broken"
                        % checked_multiprocess)
    if checked_defaults < 40:
        problems.append("only %d defaults checked: the XML or the header parser is broken" % checked_defaults)
    for p in problems:
        print("FAIL:", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
