# Sourced by take-shape.sh and take-walkthrough.sh, with w and h the screen's size: a
# visitor's mouse sweeps down onto the third wooden bar and up again. The third wooden bar's
# middle is at 21 % of the content's width; the content is centred and, on a screen narrower than
# 16:9, spans the whole width. On a portrait screen the instruments are stacked (the
# xylophone on top, its bars' tops at 30 % of the height, the third bar at 36 % of the width).
if [ "$h" -gt "$w" ]; then
  x=$(( w * 36 / 100 )); top=$(( h * 13 / 100 )); bottom=$(( h * 31 / 100 )); back=$(( h * 26 / 100 ))
else
  x=$(( w / 2 - (h * 16 / 9 < w ? h * 16 / 9 : w) * 29 / 100 )); top=$(( h * 35 / 100 )); bottom=$(( h * 62 / 100 )); back=$(( h * 52 / 100 ))
fi
for y in $(seq "$top" $(( h / 40 )) "$bottom") $(seq "$bottom" -$(( h / 25 )) "$back"); do
  xdotool mousemove "$x" "$y"; sleep 0.05
done
