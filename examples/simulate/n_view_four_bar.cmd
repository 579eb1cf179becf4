!
! A four-bar linkage written as Adams View exports a model (File > Export >
! Command File): links of steel whose mass View computes from their
! geometry, four revolute joints (a planar loop: Adams and mbexpr leave out
! the redundant equations and say which), a motion turning the crank once a
! second, gravity. Run: mbexpr simulate examples/simulate/n_view_four_bar.cmd
!
!-------------------------- Default Units for Model ---------------------------!
!
defaults units  &
   length = mm  &
   angle = deg  &
   force = newton  &
   mass = kg  &
   time = sec
!
defaults units  &
   coordinate_system_type = cartesian  &
   orientation_type = body313
!
!------------------------------ Adams View Model ------------------------------!
!
model create  &
   model_name = four_bar
!
view erase
!
!--------------------------------- Materials ----------------------------------!
!
material create  &
   material_name = .four_bar.steel  &
   adams_id = 1  &
   density = 7.801E-06  &
   youngs_modulus = 2.07E+05  &
   poissons_ratio = 0.29
!
!-------------------------------- Rigid Parts ---------------------------------!
!
!----------------------------------- ground -----------------------------------!
!
defaults coordinate_system  &
   default_coordinate_system = .four_bar.ground
!
marker create  &
   marker_name = .four_bar.ground.PIVOT_A  &
   adams_id = 1  &
   location = 0.0, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
marker create  &
   marker_name = .four_bar.ground.PIVOT_D  &
   adams_id = 2  &
   location = 400.0, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
!------------------------------------ crank ------------------------------------!
!
defaults coordinate_system  &
   default_coordinate_system = .four_bar.ground
!
part create rigid_body name_and_position  &
   part_name = .four_bar.crank  &
   adams_id = 2  &
   location = 0.0, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
defaults coordinate_system  &
   default_coordinate_system = .four_bar.crank
!
marker create  &
   marker_name = .four_bar.crank.END_A  &
   adams_id = 11  &
   location = 0.0, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
marker create  &
   marker_name = .four_bar.crank.END_B  &
   adams_id = 12  &
   location = 0.0, 100.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
part create rigid_body mass_properties  &
   part_name = .four_bar.crank  &
   material_type = .four_bar.steel
!
geometry create shape link  &
   link_name = .four_bar.crank.LINK_2  &
   i_marker = .four_bar.crank.END_A  &
   j_marker = .four_bar.crank.END_B  &
   width = 20.0  &
   depth = 10.0
!
!------------------------------------ coupler ------------------------------------!
!
defaults coordinate_system  &
   default_coordinate_system = .four_bar.ground
!
part create rigid_body name_and_position  &
   part_name = .four_bar.coupler  &
   adams_id = 3  &
   location = 0.0, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
defaults coordinate_system  &
   default_coordinate_system = .four_bar.coupler
!
marker create  &
   marker_name = .four_bar.coupler.END_B  &
   adams_id = 21  &
   location = 0.0, 100.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
marker create  &
   marker_name = .four_bar.coupler.END_C  &
   adams_id = 22  &
   location = 300.0, 250.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
part create rigid_body mass_properties  &
   part_name = .four_bar.coupler  &
   material_type = .four_bar.steel
!
geometry create shape link  &
   link_name = .four_bar.coupler.LINK_3  &
   i_marker = .four_bar.coupler.END_B  &
   j_marker = .four_bar.coupler.END_C  &
   width = 20.0  &
   depth = 10.0
!
!------------------------------------ rocker ------------------------------------!
!
defaults coordinate_system  &
   default_coordinate_system = .four_bar.ground
!
part create rigid_body name_and_position  &
   part_name = .four_bar.rocker  &
   adams_id = 4  &
   location = 0.0, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
defaults coordinate_system  &
   default_coordinate_system = .four_bar.rocker
!
marker create  &
   marker_name = .four_bar.rocker.END_C  &
   adams_id = 31  &
   location = 300.0, 250.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
marker create  &
   marker_name = .four_bar.rocker.END_D  &
   adams_id = 32  &
   location = 400.0, 0.0, 0.0  &
   orientation = 0.0d, 0.0d, 0.0d
!
part create rigid_body mass_properties  &
   part_name = .four_bar.rocker  &
   material_type = .four_bar.steel
!
geometry create shape link  &
   link_name = .four_bar.rocker.LINK_4  &
   i_marker = .four_bar.rocker.END_C  &
   j_marker = .four_bar.rocker.END_D  &
   width = 20.0  &
   depth = 10.0
!
!----------------------------------- Joints -----------------------------------!
!
constraint create joint revolute  &
   joint_name = .four_bar.JOINT_A  &
   adams_id = 1  &
   i_marker_name = .four_bar.crank.END_A  &
   j_marker_name = .four_bar.ground.PIVOT_A
!
constraint create joint revolute  &
   joint_name = .four_bar.JOINT_B  &
   adams_id = 2  &
   i_marker_name = .four_bar.coupler.END_B  &
   j_marker_name = .four_bar.crank.END_B
!
constraint create joint revolute  &
   joint_name = .four_bar.JOINT_C  &
   adams_id = 3  &
   i_marker_name = .four_bar.rocker.END_C  &
   j_marker_name = .four_bar.coupler.END_C
!
constraint create joint revolute  &
   joint_name = .four_bar.JOINT_D  &
   adams_id = 4  &
   i_marker_name = .four_bar.rocker.END_D  &
   j_marker_name = .four_bar.ground.PIVOT_D
!
!----------------------------------- Motions ----------------------------------!
!
constraint create motion_generator  &
   motion_name = .four_bar.MOTION_1  &
   adams_id = 1  &
   type_of_freedom = rotational  &
   joint_name = .four_bar.JOINT_A  &
   time_derivative = displacement  &
   function = ""
!
!----------------------------------- Forces -----------------------------------!
!
force create body gravitational  &
   gravity_field_name = gravity  &
   x_component_gravity = 0.0  &
   y_component_gravity = -9806.65  &
   z_component_gravity = 0.0
!
!---------------------------------- Requests ----------------------------------!
!
output_control create request  &
   request_name = .four_bar.DRIVE  &
   adams_id = 1  &
   f2 = ""  &
   f3 = ""  &
   f4 = ""
!
!---------------------------- Function definitions ----------------------------!
!
constraint modify motion_generator  &
   motion_name = .four_bar.MOTION_1  &
   function = "360d * time"
!
output_control modify request  &
   request_name = .four_bar.DRIVE  &
   f2 = "AZ(.four_bar.rocker.END_D, .four_bar.ground.PIVOT_D) * RTOD"  &
   f3 = "MOTION(.four_bar.MOTION_1, 0, 8, 0)"  &
   f4 = "JOINT(.four_bar.JOINT_D, 0, 2, 0)"
!
!----------------------------- Simulation Scripts -----------------------------!
!
simulation script create  &
   sim_script_name = .four_bar.Last_Sim  &
   commands =   &
              "simulation single_run transient type=auto_select initial_static=no end_time=1.0 number_of_steps=20 model_name=.four_bar"
!
