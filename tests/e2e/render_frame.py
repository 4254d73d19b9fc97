"""Runs inside ParaView's pvpython (tests/e2e/check_paraview.py starts it on a virtual X
display): opens an XDMF file of ffrsim, goes to time T, colours the bodies by von Mises
stress, saves a PNG
and writes what ParaView read (times, bounds, von Mises range, points, cells) as JSON.

usage: pvpython render_frame.py RESULT.xdmf T OUT.png OUT.json
"""
import json
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene, GetDisplayProperties,
                             ResetCamera, SaveScreenshot, Show, XDMFReader)

xdmf, t, png, out = sys.argv[1], float(sys.argv[2]), sys.argv[3], sys.argv[4]
reader = XDMFReader(FileNames=[xdmf])
reader.PointArrayStatus = ["displacement", "von_mises"]
times = list(reader.TimestepValues)
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = t
reader.UpdatePipeline(t)
info = reader.GetDataInformation()
vm = reader.PointData["von_mises"].GetRange()
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [800, 600]
view.OrientationAxesVisibility = 0
view.Background = [1.0, 1.0, 1.0]
try:  # ParaView >= 5.10 uses the colour palette unless told otherwise
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
Show(reader, view)
ColorBy(GetDisplayProperties(reader, view), ("POINTS", "von_mises"))
GetDisplayProperties(reader, view).RescaleTransferFunctionToDataRange(True, False)
view.CameraPosition = [0.0, 0.0, 1.0]
view.CameraFocalPoint = [0.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 1.0, 0.0]
ResetCamera(view)
view.ViewTime = t
SaveScreenshot(png, view, ImageResolution=[800, 600])
with open(out, "w") as f:
    json.dump({"times": times, "time": t, "bounds": list(info.GetBounds()),
               "von_mises_range": list(vm), "points": info.GetNumberOfPoints(),
               "cells": info.GetNumberOfCells()}, f)
