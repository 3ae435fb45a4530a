"""The first use of "Hybrid Octree Volume" in the real ParaView GUI, run inside
`paraview --script` by run_first_use.py (which reads the result file).

Steps, each after the GUI's event loop has run (Qt timers):

1. the plugin is already loaded (PV_PLUGIN_PATH): the welcome dialog is
   closed; Output Messages must be empty;
2. the image is opened with ParaView's reader and shown (Outline);
3. "Hybrid Octree Volume" is picked in the representation combo box of the
   Properties panel, as a user picks it: the view must show the image
   coloured by its first point array, the isovalue at mid-range, the
   Python trace must hold the pick and the colouring; the picture is saved;
4. the panel is read: volume controls shown, surface styling hidden, the
   region-of-interest sphere hidden while the region is off, the budget a
   slider up to the full-resolution bytes, the statistics in advanced mode;
5. the region of interest on: its panel (and sphere) appear;
6. "Volume" is picked the same way: its picture is saved (the reference);
7. Output Messages must still be empty;
8. a state holding the representation in a solid colour with isovalue 0 is
   saved and loaded: loading must leave both as they are;
9. results written, ParaView quits.

PyQt5 (Debian's python3-pyqt5, built on the same Qt 5 as ParaView) reads
the widgets; paraview.simple reads the proxies and saves the pictures.
"""
import json
import os
import time
import traceback

from paraview.simple import (ColorBy, Delete, FindSource, GetActiveSource, GetActiveView,
                             GetDisplayProperties, LoadState, Render, SaveScreenshot, SaveState,
                             SetActiveSource, Show, XMLImageDataReader)
from paraview import smtrace
from PyQt5 import QtCore, QtWidgets

RESULT = os.environ["HO_GUI_RESULT"]
DATA = os.environ["HO_GUI_DATA"]
SHOTS = os.environ["HO_GUI_SHOTS"]
SIZE = [400, 400]
STEP_MS = int(os.environ.get("HO_GUI_STEP_MS", "3000"))

app = QtWidgets.QApplication.instance()
result = {"checks": [], "errors": []}


def class_name(obj):
    return obj.metaObject().className()


def widgets_of_class(name):
    found = []
    for top in app.topLevelWidgets():
        if class_name(top) == name:
            found.append(top)
        found += [w for w in top.findChildren(QtWidgets.QWidget) if class_name(w) == name]
    return found


def check(name, ok, detail=""):
    result["checks"].append({"name": name, "ok": bool(ok), "detail": str(detail)})


def output_messages():
    """The text of the Output Messages window (its console and message list)."""
    texts = []
    for widget in widgets_of_class("pqOutputWidget"):
        for edit in widget.findChildren(QtWidgets.QTextEdit):
            texts.append(edit.toPlainText())
        for view in widget.findChildren(QtWidgets.QTreeView):
            model = view.model()
            for row in range(model.rowCount() if model else 0):
                texts.append(str(model.index(row, 0).data()))
    return "\n".join(t for t in texts if t.strip())


def representation_combo():
    """The representation combo box of the Properties panel (the one shown)."""
    for widget in widgets_of_class("pqDisplayRepresentationWidget"):
        for combo in widget.findChildren(QtWidgets.QComboBox):
            if combo.isVisible():
                return combo
    raise RuntimeError("no visible representation combo box")


def accept_prompt():
    """Answers Yes to ParaView's "Are you sure?" before switching to Volume."""
    for box in app.topLevelWidgets():
        if isinstance(box, QtWidgets.QMessageBox) and box.isVisible():
            result["prompts"] = result.get("prompts", 0) + 1
            box.button(QtWidgets.QMessageBox.Yes).click()


def pick(text):
    # The prompt is modal: answered from a timer running in its event loop.
    QtCore.QTimer.singleShot(1000, accept_prompt)
    combo = representation_combo()
    index = combo.findText(text)
    if index < 0:
        raise RuntimeError("%r not offered: %s" % (text, [combo.itemText(i) for i in range(combo.count())]))
    combo.setCurrentIndex(index)  # what a click on the item does


def wait_for(predicate, seconds=30.0):
    """Processes Qt events until `predicate()` holds or `seconds` pass (a loaded
    machine may take longer than a step to update the panel); its last value."""
    deadline = time.monotonic() + seconds
    value = predicate()
    while not value and time.monotonic() < deadline:
        QtWidgets.QApplication.processEvents(QtCore.QEventLoop.AllEvents, 100)
        time.sleep(0.05)
        value = predicate()
    return value


def display_panel():
    """The pqProxyWidget of the active representation (holds 'Representation')."""
    for panel in widgets_of_class("pqProxyWidget"):
        if panel.isVisible() and panel.findChild(QtWidgets.QWidget, "Representation"):
            return panel
    raise RuntimeError("no display panel")


def shown(names):
    """Which of the property widgets `names` the display panel shows."""
    panel = display_panel()
    out = {}
    for name in names:
        widget = panel.findChild(QtWidgets.QWidget, name)
        out[name] = bool(widget and widget.isVisible())
    return out


def set_advanced(on):
    """The gear button of the Properties panel (show advanced properties)."""
    for panel in widgets_of_class("pqPropertiesPanel"):
        for button in panel.findChildren(QtWidgets.QAbstractButton):
            if button.isCheckable() and "advanced" in (button.toolTip() + button.objectName()).lower():
                if button.isChecked() != on:
                    button.click()
                return True
    return False


def save(name):
    path = os.path.join(SHOTS, name)
    SaveScreenshot(path, GetActiveView(), ImageResolution=SIZE)
    return path


def step_start():
    for dialog in app.topLevelWidgets():
        if isinstance(dialog, QtWidgets.QDialog) and dialog.isVisible():
            dialog.reject()  # the welcome dialog
    result["messages_after_load"] = output_messages()
    check("no output message after loading the plugin", not result["messages_after_load"],
          result["messages_after_load"])


def step_open():
    reader = XMLImageDataReader(registrationName="image.vti", FileName=[DATA])
    SetActiveSource(reader)
    Show(reader, GetActiveView())
    view = GetActiveView()
    view.OrientationAxesVisibility = 0
    Render(view)
    result["arrays"] = list(reader.PointData.keys())
    result["range"] = list(reader.PointData[result["arrays"][0]].GetRange())


def step_pick_hybrid():
    smtrace.start_trace()
    pick("Hybrid Octree Volume")


def step_read_hybrid():
    trace = smtrace.stop_trace()
    result["trace"] = trace
    check("the Python trace holds the pick and the colouring",
          "Hybrid Octree Volume" in trace and "ColorBy(" in trace, trace[-600:])
    display = GetDisplayProperties(GetActiveSource(), GetActiveView())
    Render(GetActiveView())
    color = list(display.ColorArrayName)
    check("coloured by the first point array", color == ["POINTS", result["arrays"][0]], color)
    lo, hi = result["range"]
    check("isovalue at mid-range", abs(display.OctreeIsovalue - 0.5 * (lo + hi)) <= 1e-9 * max(1.0, abs(hi)),
          display.OctreeIsovalue)
    result["hybrid_png"] = save("hybrid.png")
    default = shown(["BlendMode", "UseCropping", "TextureBudgetMB", "ShowIsosurface", "OctreeIsovalue",
                     "IsosurfaceColor", "UseRegionOfInterest", "Opacity", "Specular", "InteractiveSphere",
                     "LastBricks"])
    result["default_panel"] = default
    for name in ["BlendMode", "UseCropping", "TextureBudgetMB", "ShowIsosurface", "UseRegionOfInterest"]:
        check("panel shows %s" % name, default[name])
    for name in ["Opacity", "Specular", "InteractiveSphere", "LastBricks"]:
        check("panel hides %s (default mode, region off)" % name, not default[name])
    panel = display_panel()
    color_button = panel.findChild(QtWidgets.QWidget, "IsosurfaceColor")
    check("Surface Color is a colour button",
          color_button is not None and any(class_name(c) == "pqColorChooserButton" or "ColorButton" in c.objectName()
                                           for c in color_button.findChildren(QtWidgets.QWidget)))
    budget = panel.findChild(QtWidgets.QWidget, "TextureBudgetMB")
    sliders = [w for w in budget.findChildren(QtWidgets.QWidget) if class_name(w) == "pqDoubleRangeWidget"]

    def slider_max():
        return sliders[0].property("maximum") if sliders else None

    full_mb = float(os.environ["HO_GUI_FULL_MB"])
    # The range arrives with the statistics pulled after the render.
    wait_for(lambda: slider_max() is not None and abs(slider_max() - full_mb) < 0.01)
    maximum = slider_max()
    result["budget_slider_max"] = maximum
    check("budget is a slider ending at the full-resolution bytes",
          maximum is not None and abs(maximum - full_mb) < 0.01, maximum)
    check("advanced button found", set_advanced(True))


def step_read_advanced():
    advanced = shown(["Shade", "VolumeRenderingMode", "ScalarOpacityUnitDistance", "LastBricks", "LastTextureMB",
                      "LastEstimatedError", "LastPlan", "Opacity", "Specular", "Ambient"])
    result["advanced_panel"] = advanced
    for name in ["Shade", "VolumeRenderingMode", "ScalarOpacityUnitDistance", "LastBricks", "LastTextureMB",
                 "LastEstimatedError", "LastPlan"]:
        check("advanced panel shows %s" % name, advanced[name])
    for name in ["Opacity", "Specular", "Ambient"]:
        check("advanced panel hides surface %s" % name, not advanced[name])
    display = GetDisplayProperties(GetActiveSource(), GetActiveView())
    bricks = display.GetPropertyValue("LastBricks")
    check("statistics read back after the frame", bricks and bricks > 0, bricks)
    error = display.GetPropertyValue("LastEstimatedError")
    check("Estimated Error 0 where the budget holds the whole image at full resolution",
          result["budget_slider_max"] is not None and result["budget_slider_max"] < 64 and error == 0, error)
    set_advanced(False)
    display.UseRegionOfInterest = 1
    Render(GetActiveView())


def step_read_roi():
    on = shown(["InteractiveSphere"])
    check("region-of-interest sphere shown when the region is on", on["InteractiveSphere"])
    result["roi_png"] = save("hybrid-roi.png")
    display = GetDisplayProperties(GetActiveSource(), GetActiveView())
    display.UseRegionOfInterest = 0
    Render(GetActiveView())
    pick("Volume")


def step_read_volume():
    Render(GetActiveView())
    result["volume_png"] = save("volume.png")
    result["messages_at_end"] = output_messages()
    check("no output message after picking the representations", not result["messages_at_end"],
          result["messages_at_end"])


def step_hybrid_again():
    # "Volume" coloured the image already: nothing for the pick to change.
    GetDisplayProperties(GetActiveSource(), GetActiveView()).SetRepresentationType("Hybrid Octree Volume")


def step_state():
    """A state holding the representation in a solid colour with isovalue 0,
    loaded again: loading must not colour it or move the isovalue."""
    display = GetDisplayProperties(GetActiveSource(), GetActiveView())
    ColorBy(display, None)
    display.OctreeIsovalue = 0.0
    path = os.path.join(SHOTS, "solid.pvsm")
    SaveState(path)
    Delete(GetActiveSource())
    LoadState(path)


def step_read_state():
    source = FindSource("image.vti")
    display = GetDisplayProperties(source, GetActiveView())
    kept = (display.Representation, list(display.ColorArrayName)[1], display.OctreeIsovalue)
    check("a loaded state keeps its solid colour and isovalue", kept == ("Hybrid Octree Volume", "", 0.0), kept)


def finish():
    with open(RESULT, "w") as f:
        json.dump(result, f, indent=1)
    app.quit()


STEPS = [step_start, step_open, step_pick_hybrid, step_read_hybrid, step_read_advanced, step_read_roi,
         step_read_volume, step_hybrid_again, step_state, step_read_state]


def run(index):
    if index == len(STEPS):
        finish()
        return
    try:
        STEPS[index]()
    except Exception:
        result["errors"].append("%s: %s" % (STEPS[index].__name__, traceback.format_exc()))
        finish()
        return
    QtCore.QTimer.singleShot(STEP_MS, lambda: run(index + 1))


QtCore.QTimer.singleShot(STEP_MS, lambda: run(0))
