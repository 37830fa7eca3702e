CamTask = read_cam_task = solve_cam_task = None
