! The C API from FORTRAN through include/mbexpr_c.f90: compiled and run
! by tests/ffi.rs.
MODULE rows
  USE, INTRINSIC :: ISO_C_BINDING
  IMPLICIT NONE
CONTAINS
  ! Prints each output row; stops the run after ten.
  INTEGER(C_INT) FUNCTION print_row(user, time, values, count) BIND(C)
    TYPE(C_PTR), VALUE :: user
    REAL(C_DOUBLE), VALUE :: time
    TYPE(C_PTR), VALUE :: values
    INTEGER(C_SIZE_T), VALUE :: count
    REAL(C_DOUBLE), POINTER :: row(:)
    INTEGER(C_INT), POINTER :: seen
    CALL C_F_POINTER(values, row, [count])
    CALL C_F_POINTER(user, seen)
    seen = seen + 1
    WRITE (*, '(A, F5.2, 2F13.9)') '  t =', time, row
    print_row = MERGE(1, 0, seen >= 10)
  END FUNCTION print_row
END MODULE rows

PROGRAM capi
  USE mbexpr_c
  USE rows
  IMPLICIT NONE
  TYPE(mbexpr_error_t) :: error
  TYPE(C_PTR) :: program, model
  TYPE(mbexpr_settings_t) :: settings
  TYPE(mbexpr_summary_t) :: summary
  CHARACTER(LEN=2, KIND=C_CHAR), TARGET :: names(2)
  TYPE(C_PTR) :: inputs(2), columns(2)
  REAL(C_DOUBLE) :: value, gradient(2), hessian(4)
  REAL(C_DOUBLE), TARGET :: x(5), v(5)
  REAL(C_DOUBLE) :: values(5), gradients(10), hessians(20)
  INTEGER(C_INT) :: status(5)
  INTEGER(C_SIZE_T) :: failed
  INTEGER(C_INT), TARGET :: seen
  INTEGER :: p

  names(1) = 'x' // C_NULL_CHAR
  names(2) = 'v' // C_NULL_CHAR
  inputs = [C_LOC(names(1)), C_LOC(names(2))]
  IF (mbexpr_compile('IMPACT(x, v, 1, 1e4, 1.5, 10, 0.1)' // C_NULL_CHAR, &
      inputs, 2_C_SIZE_T, program, error) /= MBEXPR_OK) STOP 1

  IF (mbexpr_hessian(program, [0.95_C_DOUBLE, -1.0_C_DOUBLE], &
      [0_C_SIZE_T, 1_C_SIZE_T], 2_C_SIZE_T, value, gradient, hessian, &
      error) /= MBEXPR_OK) STOP 2
  WRITE (*, '(A, ES20.12)') 'IMPACT   ', value
  WRITE (*, '(A, 2ES20.12)') 'gradient ', gradient
  WRITE (*, '(A, 4ES20.12)') 'hessian  ', hessian

  ! In bulk: five points as two columns.
  x = [1.5_C_DOUBLE, 1.0_C_DOUBLE, 0.95_C_DOUBLE, 0.9_C_DOUBLE, 0.5_C_DOUBLE]
  v = -1.0_C_DOUBLE
  columns = [C_LOC(x), C_LOC(v)]
  IF (mbexpr_gradient_bulk(program, columns, 5_C_SIZE_T, &
      [0_C_SIZE_T, 1_C_SIZE_T], 2_C_SIZE_T, values, gradients, status, &
      0_C_SIZE_T, failed, error) /= MBEXPR_OK) STOP 3
  DO p = 1, 5
    WRITE (*, '(A, F5.2, 3ES20.12, I2)') 'x =', x(p), values(p), &
      gradients(2 * p - 1), gradients(2 * p), status(p)
  END DO
  ! The Hessians too: point p's 2 x 2 at hessians(4 * p - 3 : 4 * p).
  IF (mbexpr_hessian_bulk(program, columns, 5_C_SIZE_T, &
      [0_C_SIZE_T, 1_C_SIZE_T], 2_C_SIZE_T, values, gradients, hessians, &
      status, 1_C_SIZE_T, failed, error) /= MBEXPR_OK) STOP 6
  DO p = 1, 5
    IF (mbexpr_hessian(program, [x(p), v(p)], [0_C_SIZE_T, 1_C_SIZE_T], &
        2_C_SIZE_T, value, gradient, hessian, error) /= MBEXPR_OK) STOP 7
    WRITE (*, '(A, F5.2, 4ES20.12, A, L1)') 'x =', x(p), &
      hessians(4 * p - 3 : 4 * p), ' single: ', &
      ALL(hessians(4 * p - 3 : 4 * p) == hessian) .AND. values(p) == value
  END DO
  CALL mbexpr_program_free(program)

  ! An error with its place.
  IF (mbexpr_compile('IMPACT(x, v, 1, -1e4, 1.5, 10, 0.1)' // C_NULL_CHAR, &
      inputs, 2_C_SIZE_T, program, error) == MBEXPR_ERROR) THEN
    WRITE (*, '(A, I0, A, I0, 2A)') 'error at ', error%line, ':', &
      error%column, ': ', mbexpr_message(error)
  END IF

  ! A simulation into a FORTRAN row callback.
  IF (mbexpr_model_from_text('ball' // NEW_LINE('a') // &
      'DIFF/1, IC = 0, FUNCTION = DIF(2)' // NEW_LINE('a') // &
      'DIFF/2, IC = 5, FUNCTION = BISTOP(DIF(1), DIF(2), -1, 1, 1e5, ' // &
      '1.5, 50, 0.01)' // NEW_LINE('a') // 'END' // C_NULL_CHAR, &
      MBEXPR_DATASET, model, error) /= MBEXPR_OK) THEN
    WRITE (*, *) mbexpr_message(error)
    STOP 4
  END IF
  settings = mbexpr_settings_default()
  settings%end = 2.0_C_DOUBLE
  settings%steps = 20
  settings%rtol = 1.0E-8_C_DOUBLE
  seen = 0
  IF (mbexpr_simulate(model, settings, C_FUNLOC(print_row), C_NULL_FUNPTR, &
      C_LOC(seen), summary, error) /= MBEXPR_OK) STOP 5
  WRITE (*, '(A, I0, A, I0, A, L1)') 'columns ', &
    mbexpr_model_column_count(model), ', rows ', seen, &
    ', stopped ', summary%stopped == 1
  CALL mbexpr_model_free(model)

  ! The default method is auto: A4's ball turns stiff where it lands in its
  ! damped stop (t = 0.45), and auto takes Radau5 there.
  IF (mbexpr_model_from_text('A4' // NEW_LINE('a') // &
      'DIFF/1, IC = 0, FUNCTION = DIF(2)' // NEW_LINE('a') // &
      'DIFF/2, IC = 0, FUNCTION = BISTOP(DIF(1), DIF(2), -1, 1, 1e8, ' // &
      '1.5, 1e6, 1e-5) - 9.81' // NEW_LINE('a') // 'END' // C_NULL_CHAR, &
      MBEXPR_DATASET, model, error) /= MBEXPR_OK) STOP 8
  settings = mbexpr_settings_default()
  settings%end = 1.0_C_DOUBLE
  settings%steps = 10
  IF (mbexpr_simulate(model, settings, C_NULL_FUNPTR, C_NULL_FUNPTR, &
      C_NULL_PTR, summary, error) /= MBEXPR_OK) STOP 9
  WRITE (*, '(A, L1, A, I0, A)') 'default MBEXPR_AUTO: ', &
    settings%method == MBEXPR_AUTO, ', ', summary%method_changes, &
    ' method change(s)'
  CALL mbexpr_model_free(model)
END PROGRAM capi
