! Runs the FORTRAN example of docs/contact.md (SFOSUB) at the points of
! the C driver, so that the two examples can be read side by side.
PROGRAM DRIVE
  IMPLICIT NONE
  DOUBLE PRECISION GAPS(3), FORCE, DFDX, DFDV
  INTEGER I
  GAPS = (/ 0.0D0, 5.05D0, -5.2D0 /)
  DO I = 1, 3
    CALL SFOSUB(GAPS(I), 0.7D0, FORCE, DFDX, DFDV)
    WRITE (*, '(A, F5.2, A, ES19.12, A, ES19.12, A, ES19.12)') 'gap ', GAPS(I), &
      ': force ', FORCE, ', dF/dx ', DFDX, ", dF/dx' ", DFDV
  END DO
END PROGRAM DRIVE
