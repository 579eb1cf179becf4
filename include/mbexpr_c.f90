! mbexpr's C API for FORTRAN 2003 and later (ISO_C_BINDING): `USE mbexpr_c`.
! The calls and their rules are those of include/mbexpr.h (its structures
! are the types mbexpr_error_t, mbexpr_settings_t, mbexpr_summary_t:
! FORTRAN names ignore case, and MBEXPR_ERROR is the return code). Strings passed
! in end with C_NULL_CHAR (`'x' // C_NULL_CHAR`); a message that comes back
! is read with MBEXPR_MESSAGE, which also frees it. Sizes and indices are
! INTEGER(C_SIZE_T), indices from 0.
MODULE mbexpr_c
  USE, INTRINSIC :: ISO_C_BINDING
  IMPLICIT NONE

  INTEGER(C_INT), PARAMETER :: MBEXPR_OK = 0, MBEXPR_ERROR = 1
  INTEGER(C_INT), PARAMETER :: MBEXPR_DATASET = 0, MBEXPR_SCENE = 1
  ! MBEXPR_AUTO (mbexpr_settings_default's) takes DOP853 while the model is
  ! not stiff and Radau5 while it is.
  INTEGER(C_INT), PARAMETER :: MBEXPR_RADAU5 = 0, MBEXPR_DOP853 = 1, &
    MBEXPR_AUTO = 2

  TYPE, BIND(C) :: mbexpr_error_t
    TYPE(C_PTR) :: message = C_NULL_PTR
    INTEGER(C_SIZE_T) :: line = 0, column = 0
  END TYPE mbexpr_error_t

  TYPE, BIND(C) :: mbexpr_settings_t
    INTEGER(C_INT) :: method
    REAL(C_DOUBLE) :: end
    INTEGER(C_SIZE_T) :: steps
    REAL(C_DOUBLE) :: rtol, atol, h_max
    INTEGER(C_SIZE_T) :: max_steps
  END TYPE mbexpr_settings_t

  TYPE, BIND(C) :: mbexpr_summary_t
    INTEGER(C_SIZE_T) :: steps, rejected, rhs_evaluations, &
      jacobian_evaluations, lu_decompositions, events
    REAL(C_DOUBLE) :: wall_time
    INTEGER(C_INT) :: stopped
    INTEGER(C_SIZE_T) :: method_changes
  END TYPE mbexpr_summary_t

  INTERFACE
    SUBROUTINE mbexpr_error_free(error) BIND(C, NAME='mbexpr_error_free')
      IMPORT :: mbexpr_error_t
      TYPE(mbexpr_error_t), INTENT(INOUT) :: error
    END SUBROUTINE mbexpr_error_free

    INTEGER(C_INT) FUNCTION mbexpr_compile(text, inputs, input_count, &
        program, error) BIND(C, NAME='mbexpr_compile')
      IMPORT :: C_CHAR, C_PTR, C_SIZE_T, C_INT, mbexpr_error_t
      CHARACTER(KIND=C_CHAR), INTENT(IN) :: text(*)
      TYPE(C_PTR), INTENT(IN) :: inputs(*)
      INTEGER(C_SIZE_T), VALUE :: input_count
      TYPE(C_PTR), INTENT(OUT) :: program
      TYPE(mbexpr_error_t), INTENT(INOUT) :: error
    END FUNCTION mbexpr_compile

    SUBROUTINE mbexpr_program_free(program) &
        BIND(C, NAME='mbexpr_program_free')
      IMPORT :: C_PTR
      TYPE(C_PTR), VALUE :: program
    END SUBROUTINE mbexpr_program_free

    INTEGER(C_INT) FUNCTION mbexpr_value(program, point, value, error) &
        BIND(C, NAME='mbexpr_value')
      IMPORT :: C_PTR, C_DOUBLE, C_INT, mbexpr_error_t
      TYPE(C_PTR), VALUE :: program
      REAL(C_DOUBLE), INTENT(IN) :: point(*)
      REAL(C_DOUBLE), INTENT(OUT) :: value
      TYPE(mbexpr_error_t), INTENT(INOUT) :: error
    END FUNCTION mbexpr_value

    INTEGER(C_INT) FUNCTION mbexpr_gradient(program, point, wrt, wrt_count, &
        value, gradient, error) BIND(C, NAME='mbexpr_gradient')
      IMPORT :: C_PTR, C_DOUBLE, C_INT, C_SIZE_T, mbexpr_error_t
      TYPE(C_PTR), VALUE :: program
      REAL(C_DOUBLE), INTENT(IN) :: point(*)
      INTEGER(C_SIZE_T), INTENT(IN) :: wrt(*)
      INTEGER(C_SIZE_T), VALUE :: wrt_count
      REAL(C_DOUBLE), INTENT(OUT) :: value, gradient(*)
      TYPE(mbexpr_error_t), INTENT(INOUT) :: error
    END FUNCTION mbexpr_gradient

    INTEGER(C_INT) FUNCTION mbexpr_hessian(program, point, wrt, wrt_count, &
        value, gradient, hessian, error) BIND(C, NAME='mbexpr_hessian')
      IMPORT :: C_PTR, C_DOUBLE, C_INT, C_SIZE_T, mbexpr_error_t
      TYPE(C_PTR), VALUE :: program
      REAL(C_DOUBLE), INTENT(IN) :: point(*)
      INTEGER(C_SIZE_T), INTENT(IN) :: wrt(*)
      INTEGER(C_SIZE_T), VALUE :: wrt_count
      REAL(C_DOUBLE), INTENT(OUT) :: value, gradient(*), hessian(*)
      TYPE(mbexpr_error_t), INTENT(INOUT) :: error
    END FUNCTION mbexpr_hessian

    INTEGER(C_INT) FUNCTION mbexpr_value_bulk(program, columns, n, values, &
        status, threads, failed, error) BIND(C, NAME='mbexpr_value_bulk')
      IMPORT :: C_PTR, C_DOUBLE, C_INT, C_SIZE_T, mbexpr_error_t
      TYPE(C_PTR), VALUE :: program
      TYPE(C_PTR), INTENT(IN) :: columns(*)
      INTEGER(C_SIZE_T), VALUE :: n, threads
      REAL(C_DOUBLE), INTENT(OUT) :: values(*)
      INTEGER(C_INT), INTENT(OUT) :: status(*)
      INTEGER(C_SIZE_T), INTENT(OUT) :: failed
      TYPE(mbexpr_error_t), INTENT(INOUT) :: error
    END FUNCTION mbexpr_value_bulk

    INTEGER(C_INT) FUNCTION mbexpr_gradient_bulk(program, columns, n, wrt, &
        wrt_count, values, gradients, status, threads, failed, error) &
        BIND(C, NAME='mbexpr_gradient_bulk')
      IMPORT :: C_PTR, C_DOUBLE, C_INT, C_SIZE_T, mbexpr_error_t
      TYPE(C_PTR), VALUE :: program
      TYPE(C_PTR), INTENT(IN) :: columns(*)
      INTEGER(C_SIZE_T), VALUE :: n, wrt_count, threads
      INTEGER(C_SIZE_T), INTENT(IN) :: wrt(*)
      REAL(C_DOUBLE), INTENT(OUT) :: values(*), gradients(*)
      INTEGER(C_INT), INTENT(OUT) :: status(*)
      INTEGER(C_SIZE_T), INTENT(OUT) :: failed
      TYPE(mbexpr_error_t), INTENT(INOUT) :: error
    END FUNCTION mbexpr_gradient_bulk

    INTEGER(C_INT) FUNCTION mbexpr_hessian_bulk(program, columns, n, wrt, &
        wrt_count, values, gradients, hessians, status, threads, failed, &
        error) BIND(C, NAME='mbexpr_hessian_bulk')
      IMPORT :: C_PTR, C_DOUBLE, C_INT, C_SIZE_T, mbexpr_error_t
      TYPE(C_PTR), VALUE :: program
      TYPE(C_PTR), INTENT(IN) :: columns(*)
      INTEGER(C_SIZE_T), VALUE :: n, wrt_count, threads
      INTEGER(C_SIZE_T), INTENT(IN) :: wrt(*)
      REAL(C_DOUBLE), INTENT(OUT) :: values(*), gradients(*), hessians(*)
      INTEGER(C_INT), INTENT(OUT) :: status(*)
      INTEGER(C_SIZE_T), INTENT(OUT) :: failed
      TYPE(mbexpr_error_t), INTENT(INOUT) :: error
    END FUNCTION mbexpr_hessian_bulk

    INTEGER(C_INT) FUNCTION mbexpr_model_from_text(text, format, model, &
        error) BIND(C, NAME='mbexpr_model_from_text')
      IMPORT :: C_CHAR, C_PTR, C_INT, mbexpr_error_t
      CHARACTER(KIND=C_CHAR), INTENT(IN) :: text(*)
      INTEGER(C_INT), VALUE :: format
      TYPE(C_PTR), INTENT(OUT) :: model
      TYPE(mbexpr_error_t), INTENT(INOUT) :: error
    END FUNCTION mbexpr_model_from_text

    INTEGER(C_INT) FUNCTION mbexpr_model_load(path, model, error) &
        BIND(C, NAME='mbexpr_model_load')
      IMPORT :: C_CHAR, C_PTR, C_INT, mbexpr_error_t
      CHARACTER(KIND=C_CHAR), INTENT(IN) :: path(*)
      TYPE(C_PTR), INTENT(OUT) :: model
      TYPE(mbexpr_error_t), INTENT(INOUT) :: error
    END FUNCTION mbexpr_model_load

    INTEGER(C_SIZE_T) FUNCTION mbexpr_model_column_count(model) &
        BIND(C, NAME='mbexpr_model_column_count')
      IMPORT :: C_PTR, C_SIZE_T
      TYPE(C_PTR), VALUE :: model
    END FUNCTION mbexpr_model_column_count

    SUBROUTINE mbexpr_model_free(model) BIND(C, NAME='mbexpr_model_free')
      IMPORT :: C_PTR
      TYPE(C_PTR), VALUE :: model
    END SUBROUTINE mbexpr_model_free

    TYPE(mbexpr_settings_t) FUNCTION mbexpr_settings_default() &
        BIND(C, NAME='mbexpr_settings_default')
      IMPORT :: mbexpr_settings_t
    END FUNCTION mbexpr_settings_default

    ! ROW is a BIND(C) function (user, time, values, count) returning
    ! INTEGER(C_INT) 0 to go on (pass it with C_FUNLOC); EVENT may be
    ! C_NULL_FUNPTR.
    INTEGER(C_INT) FUNCTION mbexpr_simulate(model, settings, row, event, &
        user, summary, error) BIND(C, NAME='mbexpr_simulate')
      IMPORT :: C_PTR, C_FUNPTR, C_INT, mbexpr_settings_t, mbexpr_summary_t, &
        mbexpr_error_t
      TYPE(C_PTR), VALUE :: model
      TYPE(mbexpr_settings_t), INTENT(IN) :: settings
      TYPE(C_FUNPTR), VALUE :: row, event
      TYPE(C_PTR), VALUE :: user
      TYPE(mbexpr_summary_t), INTENT(OUT) :: summary
      TYPE(mbexpr_error_t), INTENT(INOUT) :: error
    END FUNCTION mbexpr_simulate
  END INTERFACE

CONTAINS

  ! The message of ERROR as a FORTRAN string ('' when there is none); the
  ! message is freed.
  FUNCTION mbexpr_message(error) RESULT(text)
    TYPE(mbexpr_error_t), INTENT(INOUT) :: error
    CHARACTER(LEN=:), ALLOCATABLE :: text
    CHARACTER(KIND=C_CHAR), POINTER :: chars(:)
    INTEGER :: length
    INTERFACE
      INTEGER(C_SIZE_T) FUNCTION strlen(s) BIND(C, NAME='strlen')
        IMPORT :: C_PTR, C_SIZE_T
        TYPE(C_PTR), VALUE :: s
      END FUNCTION strlen
    END INTERFACE
    INTEGER :: i
    IF (.NOT. C_ASSOCIATED(error%message)) THEN
      text = ''
      RETURN
    END IF
    length = INT(strlen(error%message))
    CALL C_F_POINTER(error%message, chars, [length])
    ALLOCATE(CHARACTER(LEN=length) :: text)
    DO i = 1, length
      text(i:i) = chars(i)
    END DO
    CALL mbexpr_error_free(error)
  END FUNCTION mbexpr_message
END MODULE mbexpr_c
