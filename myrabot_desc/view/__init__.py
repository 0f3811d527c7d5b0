"""See the robot: the scene built from the model (scene.py), the web viewer (server.py) and the
facts it draws that no other command computes (facts.py). ``render`` draws the same scene offscreen."""
