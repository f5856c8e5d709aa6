; Example Hyrel job (Repetrel v5 addressing) with a few mistakes for gclint to find
; gclint: dialect=hyrel
M6 T0 O1 X0 Y0 Z0                  ; head declarations, as Repetrel writes them
M6 T1 O2 X25 Y0 Z0                 ; T1 is loaded, but no T command calls it
G21                                ; millimetres
G90                                ; absolute positioning
G28 X0 Y0                          ; home X and Y
M106 C255                          ; fan values 0-255 from here on
M229 E1 D0                         ; use E values -- but D0 is illegal with E1
M109 T40 S215                      ; wait on "all devices": the wait fails
M109 T0 S215 H210 L5               ; H and L together
T0
G1 Z0.3 F600
G1 X50 Y50 E1.2 F1800
G1 X60 Y50 E2.4
T4                                 ; a 30M has no fifth position
M30
