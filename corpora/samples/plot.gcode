; plot.gcode — a hand-made sample plot for the stepzip README demo.
; Written by hand for this project (not taken from any other source).
; Coordinates are in steps (integers); G0 lifts the pen and starts a new
; chain, G1 draws a line, G2/G3 draw clockwise/counter-clockwise arcs whose
; centre is given by I J relative to the arc's start.
%
G90 G17
M3 (pen down signal: ignored, only G0 breaks paths)

; a square, 40 x 40
G0 X0 Y0
G1 X40 Y0 F1500
G1 X40 Y40
G1 X0 Y40
G1 X0 Y0

; a full circle of radius 20 about (80, 20)
G0 X100 Y20
G3 X100 Y20 I-20 J0

; a triangle with slanted sides
G0 X120 Y0
G1 X170 Y0
G1 X145 Y43
G1 X120 Y0

; a rounded rectangle: straight sides joined by quarter circles of radius 8
G0 X8 Y60
G1 X62 Y60
G3 X70 Y68 I0 J8
G1 X70 Y92
G3 X62 Y100 I-8 J0
G1 X8 Y100
G3 X0 Y92 I0 J-8
G1 X0 Y68
G3 X8 Y60 I8 J0

; a zig-zag in relative coordinates
G0 X90 Y60
G91
G1 X10 Y30
G1 X10 Y-30
G1 X10 Y30
G1 X10 Y-30
G1 X10 Y30
G90

; a wave of half circles, clockwise and counter-clockwise
G0 X90 Y110
G2 X110 Y110 I10 J0
G3 X130 Y110 I10 J0
G2 X150 Y110 I10 J0
G3 X170 Y110 I10 J0
M5
M2
%
