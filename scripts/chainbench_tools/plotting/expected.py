# SPDX-License-Identifier: MIT
"""Where a scene's expectations (its "expect" entries in a chainbench.run/1 JSON) put its bodies:
expected centres with their tolerance, and bounds on centres, for drawing over final states.
"""
from .common import number


def expected_marks(scene, limit=300):
    """(targets, bounds, left out). targets: {x, y, tolerance, body (index), final (checked on
    the last state only), text} for the centre each centre or moved entry expects (a "*" entry
    one per dynamic body, unless they are more than `limit`: then it is left out whole, and
    named in the third list); moved entries need the scene's initial centres ("centers") and are
    left out without them. bounds: (axis 0|1, value, text) for each bound an entry puts on a
    centre, the text on the first bound of each entry and axis ("" on the other)."""
    names, kinds = scene.get("names") or [], scene.get("kinds") or []
    centers = scene.get("centers")
    index = {name: i for i, name in enumerate(names)}
    targets, bounds, left_out = [], [], []
    for k, e in enumerate(scene.get("expect") or []):
        body = e.get("body")
        if body == "*":
            bodies = [i for i, kind in enumerate(kinds) if kind == "dynamic"]
            if len(bodies) > limit and e.get("kind") in ("moved", "center"):
                left_out.append(f"expect[{k}] ({len(bodies)} bodies)")
                continue
        else:
            bodies = [index[body]] if body in index else []
        final = "from_step" not in e and "to_step" not in e
        window = "" if final else f" (steps {e.get('from_step', 0)}-{e.get('to_step', '')})"
        kind = e.get("kind")
        tolerance = number(e.get("tolerance")) or 0.0
        if kind == "center" and isinstance(e.get("center"), list) and bodies:
            x, y = (number(v) for v in e["center"])
            if x is not None and y is not None:
                targets.append({"x": x, "y": y, "tolerance": tolerance, "body": bodies[0],
                                "final": final, "text": f"expect[{k}] {body}{window}"})
        elif kind == "moved" and centers and isinstance(e.get("moved"), list):
            dx, dy = (number(v) or 0.0 for v in e["moved"])
            for i in bodies:
                x, y = (number(v) for v in centers[i])
                if x is not None and y is not None:
                    targets.append({"x": x + dx, "y": y + dy, "tolerance": tolerance, "body": i,
                                    "final": final, "text": f"expect[{k}] {names[i]}{window}"})
        elif kind == "bounds":
            for axis, letter in ((0, "x"), (1, "y")):
                low = number((e.get("min") or [None, None])[axis])
                high = number((e.get("max") or [None, None])[axis])
                if low is None and high is None:
                    continue
                text = (f"expect[{k}] {body}: " + (f"{low:g} <= " if low is not None else "") +
                        letter + (f" <= {high:g}" if high is not None else "") + window)
                for n, value in enumerate(v for v in (low, high) if v is not None):
                    bounds.append((axis, value, text if n == 0 else ""))
    return targets, bounds, left_out
