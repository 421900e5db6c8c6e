; Reference laser gate, PIC16F628A subset (docs/gate-firmware.md, "The PIC"), gpasm.
; 4 MHz crystal (XT), instruction cycle 1 us. USART 9600 8N1 (BRGH 1, SPBRG 25: 9615 baud), polled.
; Pulse train: CCP1 PWM on RB3 from Timer2 (hardware), 2 us pulses (4 us below 977 Hz).
; Implements: *IDN?, PING, OFF, FREQ <hz> (0, or 245..100000: the PWM's range at 4 MHz), STATE?, WDOG <ms> (0 or
; 50..60000) and the watchdog (Timer0, 1 ms tick) with TRIPPED in STATE?. Not yet: BURST (answered ERR 1 UNKNOWN),
; FREQ 1..244 (ERR 2 RANGE), keywords in lower case, tabs, several spaces, signs (ERR 1 / ERR 3), lines over 24 bytes
; (ERR 1 UNKNOWN, as the full protocol does over 128).
        processor p16f628a
        radix dec
        #include <p16f628a.inc>
        __config _XT_OSC & _WDT_OFF & _PWRTE_ON & _MCLRE_ON & _BOREN_ON & _LVP_OFF & _CP_OFF
        errorlevel -302

LINEMAX equ 24
        cblock 0x20
          line:LINEMAX
          len, over
          num0, num1, num2
          dig:7
          ndig
          fdig:7
          wdig:6
          wd0, wd1
          ms0, ms1
          flags
          tmp, cnt, ptr, src
          q0, q1, q2, r0, r1, r2, d0, d1, d2
          t0, t1, t2
          txc
        endc
FIRING  equ 0
TRIPPED equ 1

        org 0
        goto start

; ---- message table (retlw), each message ends with 0 ----
        org 0x10
msg:    movwf PCL               ; PCLATH = 0, table inside the first 256 words
m_idn   equ $
        dt "OK PICGATE PIC-0.1", 0
m_pong  equ $
        dt "OK PONG", 0
m_off   equ $
        dt "OK FREQ 0", 0
m_freq  equ $
        dt "OK FREQ ", 0
m_wdog  equ $
        dt "OK WDOG ", 0
m_state equ $
        dt "OK STATE ", 0
m_on    equ $
        dt " ON WDOG ", 0
m_noton equ $
        dt " OFF WDOG ", 0
m_trip  equ $
        dt " TRIPPED", 0
m_e1    equ $
        dt "ERR 1 UNKNOWN", 0
m_e2    equ $
        dt "ERR 2 RANGE", 0
m_e3    equ $
        dt "ERR 3 SYNTAX", 0

start:
        clrf PORTB
        movlw 0x07
        movwf CMCON             ; comparators off
        bsf STATUS, RP0
        movlw b'11110111'       ; RB3 (CCP1) output, RB1 RX / RB2 TX as the USART wants
        movwf TRISB
        movlw 25
        movwf SPBRG
        movlw b'00100100'       ; TXEN, BRGH
        movwf TXSTA
        movlw b'11010001'       ; Timer0: internal clock, prescaler 1:4 (pull-ups off)
        movwf OPTION_REG
        bcf STATUS, RP0
        movlw b'10010000'       ; SPEN, CREN
        movwf RCSTA
        clrf CCP1CON
        clrf T2CON
        clrf len
        clrf over
        clrf flags
        clrf ms0
        clrf ms1
        movlw low 1000          ; watchdog 1000 ms at power-up
        movwf wd0
        movlw high 1000
        movwf wd1
        movlw '1'
        movwf wdig
        movlw '0'
        movwf wdig+1
        movwf wdig+2
        movwf wdig+3
        clrf wdig+4
        movlw '0'
        movwf fdig
        clrf fdig+1
        movlw 6
        movwf TMR0
        bcf INTCON, T0IF

loop:   btfsc INTCON, T0IF
        call tick
        btfsc RCSTA, OERR       ; overrun: restart the receiver
        call rx_restart
        btfss PIR1, RCIF
        goto loop
        movf RCREG, W
        movwf tmp
        xorlw 0x0A
        btfsc STATUS, Z
        goto got_line
        movlw LINEMAX
        subwf len, W            ; C set when len >= LINEMAX
        btfsc STATUS, C
        goto too_long
        movlw line
        addwf len, W
        movwf FSR
        movf tmp, W
        movwf INDF
        incf len, F
        goto loop
too_long:
        bsf over, 0
        goto loop
got_line:
        call do_line
        clrf len
        clrf over
        goto loop

rx_restart:
        bcf RCSTA, CREN
        bsf RCSTA, CREN
        return

; ---- 1 ms tick: counts the silence; switches off when it reaches the watchdog time while firing ----
tick:   bcf INTCON, T0IF
        movlw 8                 ; 250 counts of 4 us (the write costs two)
        addwf TMR0, F
        incfsz ms0, F
        goto tick_chk
        incfsz ms1, F
        goto tick_chk
        decf ms1, F             ; saturate at 0xFFFF
        decf ms0, F
tick_chk:
        btfss flags, FIRING
        return
        movf wd0, W
        iorwf wd1, W
        btfsc STATUS, Z
        return                  ; watchdog off
        movf ms1, W             ; ms > wd ? (so never before the watchdog time, at most a tick after it)
        subwf wd1, W            ; wd1 - ms1: a borrow means ms1 > wd1
        btfss STATUS, C
        goto trip
        btfss STATUS, Z
        return
        movf ms0, W
        subwf wd0, W
        btfsc STATUS, C
        return
trip:   call pwm_off
        bsf flags, TRIPPED
        return

; ---- a line has arrived ----
do_line:
        clrf ms0                ; any line feeds the watchdog
        clrf ms1
        btfsc over, 0
        goto err1
        movf len, W             ; drop a trailing '\r'
        btfsc STATUS, Z
        return
        addlw line - 1
        movwf FSR
        movf INDF, W
        xorlw 0x0D
        btfsc STATUS, Z
        decf len, F
        movf len, W
        btfsc STATUS, Z
        return                  ; empty line: heard, not answered
        ; *IDN?
        movlw 5
        xorwf len, W
        btfss STATUS, Z
        goto not_idn
        movf line, W
        xorlw '*'
        btfss STATUS, Z
        goto not_idn
        movf line+1, W
        xorlw 'I'
        btfss STATUS, Z
        goto not_idn
        movf line+4, W
        xorlw '?'
        btfss STATUS, Z
        goto not_idn
        movlw m_idn
        goto reply
not_idn:
        ; PING
        movlw 4
        xorwf len, W
        btfss STATUS, Z
        goto not_ping
        movf line, W
        xorlw 'P'
        btfss STATUS, Z
        goto not_ping
        movf line+1, W
        xorlw 'I'
        btfss STATUS, Z
        goto not_ping
        movf line+3, W
        xorlw 'G'
        btfss STATUS, Z
        goto not_ping
        movlw m_pong
        goto reply
not_ping:
        ; OFF
        movlw 3
        xorwf len, W
        btfss STATUS, Z
        goto not_off
        movf line, W
        xorlw 'O'
        btfss STATUS, Z
        goto not_off
        movf line+2, W
        xorlw 'F'
        btfss STATUS, Z
        goto not_off
        call pwm_off
        movlw m_off
        goto reply
not_off:
        ; STATE?
        movlw 6
        xorwf len, W
        btfss STATUS, Z
        goto not_state
        movf line, W
        xorlw 'S'
        btfss STATUS, Z
        goto not_state
        movf line+5, W
        xorlw '?'
        btfss STATUS, Z
        goto not_state
        goto state
not_state:
        ; FREQ and WDOG: keyword, one space, digits
        movf line, W
        xorlw 'F'
        btfss STATUS, Z
        goto not_freq
        movf line+1, W
        xorlw 'R'
        btfss STATUS, Z
        goto not_freq
        movf line+3, W
        xorlw 'Q'
        btfss STATUS, Z
        goto not_freq
        movlw 4
        xorwf len, W
        btfsc STATUS, Z
        goto err3               ; FREQ alone
        movf line+4, W
        xorlw ' '
        btfss STATUS, Z
        goto err1
        movlw line + 5
        call parse
        xorlw 0
        btfss STATUS, Z
        goto err_w
        goto freq
not_freq:
        movf line, W
        xorlw 'W'
        btfss STATUS, Z
        goto err1
        movf line+1, W
        xorlw 'D'
        btfss STATUS, Z
        goto err1
        movf line+3, W
        xorlw 'G'
        btfss STATUS, Z
        goto err1
        movlw 4
        xorwf len, W
        btfsc STATUS, Z
        goto err3
        movf line+4, W
        xorlw ' '
        btfss STATUS, Z
        goto err1
        movlw line + 5
        call parse
        xorlw 0
        btfss STATUS, Z
        goto err_w
        goto wdog

err_w:  xorlw 3                 ; parse returned 2 or 3
        btfsc STATUS, Z
        goto err3
        goto err2
err1:   movlw m_e1
        goto reply
err2:   movlw m_e2
        goto reply
err3:   movlw m_e3
        goto reply

; ---- FREQ n ----
freq:   movf num0, W
        iorwf num1, W
        iorwf num2, W
        btfsc STATUS, Z
        goto freq_zero
        ; 245 <= n <= 100000 (0x0186A0)
        movf num2, W
        btfss STATUS, Z
        goto freq_hi
        movf num1, W
        btfss STATUS, Z
        goto freq_ok
        movlw 245
        subwf num0, W
        btfss STATUS, C
        goto err2
        goto freq_ok
freq_hi:
        movlw 0x01
        subwf num2, W           ; num2 > 1 -> range
        btfss STATUS, Z
        goto err2
        movlw 0x86
        subwf num1, W
        btfss STATUS, C
        goto freq_ok            ; num1 < 0x86
        btfss STATUS, Z
        goto err2               ; num1 > 0x86
        movlw 0xA1
        subwf num0, W
        btfsc STATUS, C
        goto err2               ; num0 >= 0xA1
freq_ok:
        call pwm_on
        call keep_digits
        movlw m_freq
        call send
        movlw dig
        goto send_ram_line
freq_zero:
        call pwm_off
        movlw m_off
        goto reply

keep_digits:                    ; fdig = dig
        movlw 7
        movwf cnt
        movlw dig
        movwf src
        movlw fdig
        movwf ptr
kd:     movf src, W
        movwf FSR
        movf INDF, W
        movwf tmp
        movf ptr, W
        movwf FSR
        movf tmp, W
        movwf INDF
        incf src, F
        incf ptr, F
        decfsz cnt, F
        goto kd
        return

; ---- WDOG n ----
wdog:   movf num2, W
        btfss STATUS, Z
        goto err2
        movf num0, W
        iorwf num1, W
        btfsc STATUS, Z
        goto wdog_ok
        movf num1, W            ; >= 50
        btfss STATUS, Z
        goto wdog_max
        movlw 50
        subwf num0, W
        btfss STATUS, C
        goto err2
wdog_max:                       ; <= 60000 (0xEA60)
        movlw 0xEA
        subwf num1, W
        btfss STATUS, C
        goto wdog_ok
        btfss STATUS, Z
        goto err2
        movlw 0x61
        subwf num0, W
        btfsc STATUS, C
        goto err2
wdog_ok:
        movf num0, W
        movwf wd0
        movf num1, W
        movwf wd1
        movlw 6
        movwf cnt
        movlw dig
        movwf src
        movlw wdig
        movwf ptr
        call kd
        movlw m_wdog
        call send
        movlw dig
        goto send_ram_line

; ---- STATE? ----
state:  movlw m_state
        call send
        movlw fdig
        call send_ram
        movlw m_on
        btfss flags, FIRING
        movlw m_noton
        call send
        movlw wdig
        call send_ram
        btfss flags, TRIPPED
        goto state_end
        movlw m_trip
        call send
        bcf flags, TRIPPED
state_end:
        goto line_end

; ---- parse: digits from W (a line address) to the line's end -> num (24 bits) and dig (no leading zeros) ----
; returns W = 0 ok, 3 not a number, 2 more than six significant digits
parse:  movwf FSR
        clrf num0
        clrf num1
        clrf num2
        clrf ndig
        movlw line
        addwf len, W
        movwf tmp               ; end address
        movf FSR, W
        xorwf tmp, W
        btfsc STATUS, Z
        retlw 3                 ; nothing after the space
p_next: movf FSR, W
        xorwf tmp, W
        btfsc STATUS, Z
        goto p_done
        movf INDF, W
        addlw 0xD0              ; - '0'
        movwf t0                ; digit value if a digit
        movlw 10
        subwf t0, W
        btfsc STATUS, C
        retlw 3                 ; not 0..9
        incf FSR, F
        movf t0, W
        iorwf ndig, W           ; leading zero: skip
        btfsc STATUS, Z
        goto p_next
        movlw 6
        subwf ndig, W
        btfsc STATUS, C
        retlw 2                 ; seventh significant digit
        movf FSR, W             ; keep FSR while storing the digit
        movwf src
        movlw dig
        addwf ndig, W
        movwf FSR
        movf t0, W
        addlw '0'
        movwf INDF
        incf ndig, F
        movf src, W
        movwf FSR
        ; num = num * 10 + digit
        bcf STATUS, C
        rlf num0, F
        rlf num1, F
        rlf num2, F             ; x2
        movf num0, W
        movwf t1
        movf num1, W
        movwf r1
        movf num2, W
        movwf r2                ; r = x2
        bcf STATUS, C
        rlf num0, F
        rlf num1, F
        rlf num2, F
        bcf STATUS, C
        rlf num0, F
        rlf num1, F
        rlf num2, F             ; x8
        movf t1, W
        addwf num0, F
        movf r1, W
        btfsc STATUS, C
        incfsz r1, W
        addwf num1, F
        movf r2, W
        btfsc STATUS, C
        incfsz r2, W
        addwf num2, F           ; x10
        movf t0, W
        addwf num0, F
        btfss STATUS, C
        goto p_next
        incfsz num1, F
        goto p_next
        incf num2, F
        goto p_next
p_done: movf ndig, W            ; all zeros: "0"
        btfss STATUS, Z
        goto p_term
        movlw '0'
        movwf dig
        incf ndig, F
p_term: movlw dig
        addwf ndig, W
        movwf FSR
        clrf INDF
        retlw 0

; ---- the PWM ----
pwm_off:
        clrf CCP1CON            ; RB3 back to its latch, low
        clrf T2CON
        bcf flags, FIRING
        movlw '0'               ; STATE? says 0 Hz
        movwf fdig
        clrf fdig+1
        return

; period in us = (1000000 + n/2) / n, then Timer2's prescaler and PR2
pwm_on: call pwm_off
        movf num0, W
        movwf d0
        movf num1, W
        movwf d1
        movf num2, W
        movwf d2
        movlw 0x40              ; 1000000 = 0x0F4240
        movwf q0
        movlw 0x42
        movwf q1
        movlw 0x0F
        movwf q2
        bcf STATUS, C           ; + n / 2
        rrf d2, W
        movwf t2
        rrf d1, W
        movwf t1
        rrf d0, W
        addwf q0, F
        movf t1, W
        btfsc STATUS, C
        incfsz t1, W
        addwf q1, F
        movf t2, W
        btfsc STATUS, C
        incfsz t2, W
        addwf q2, F
        call div24              ; q = period in us (<= 4082)
        ; <= 256: prescaler 1, PR2 = P - 1, duty 8 quarter-cycles (2 us)
        movf q1, W
        btfsc STATUS, Z
        goto pre1
        movlw 1
        xorwf q1, W
        btfss STATUS, Z
        goto not1
        movf q0, W
        btfsc STATUS, Z
        goto pre1               ; exactly 256
not1:   ; <= 1024: prescaler 4, PR2 = (P + 2) / 4 - 1, duty 2 units of 1 us
        movlw 4
        subwf q1, W
        btfss STATUS, C
        goto pre4
        btfss STATUS, Z
        goto pre16
        movf q0, W
        btfsc STATUS, Z
        goto pre4               ; exactly 1024
pre16:  movlw 8                 ; PR2 = (P + 8) / 16 - 1, duty 1 unit of 4 us
        addwf q0, F
        btfsc STATUS, C
        incf q1, F
        movlw 4
        call shift_q
        movlw b'00000110'       ; TMR2ON, 1:16
        movwf tmp
        clrf CCPR1L
        movlw b'00011100'       ; PWM, DC1B = 01
        goto pwm_start
pre4:   movlw 2
        addwf q0, F
        btfsc STATUS, C
        incf q1, F
        movlw 2
        call shift_q
        movlw b'00000101'       ; TMR2ON, 1:4
        movwf tmp
        clrf CCPR1L
        movlw b'00101100'       ; PWM, DC1B = 10
        goto pwm_start
pre1:   movlw b'00000100'       ; TMR2ON, 1:1
        movwf tmp
        movlw 2
        movwf CCPR1L
        movlw b'00001100'       ; PWM, DC1B = 00
pwm_start:
        movwf CCP1CON
        decf q0, W              ; PR2 = q - 1
        bsf STATUS, RP0
        movwf PR2
        bcf STATUS, RP0
        movwf TMR2              ; at PR2: the first increment starts the first pulse
        movf tmp, W
        movwf T2CON
        bsf flags, FIRING
        return

shift_q:                        ; q1:q0 >>= W
        movwf cnt
sq:     bcf STATUS, C
        rrf q1, F
        rrf q0, F
        decfsz cnt, F
        goto sq
        return

; q2:q1:q0 / d2:d1:d0 -> quotient in q, remainder in r
div24:  clrf r0
        clrf r1
        clrf r2
        movlw 24
        movwf cnt
d_loop: bcf STATUS, C
        rlf q0, F
        rlf q1, F
        rlf q2, F
        rlf r0, F
        rlf r1, F
        rlf r2, F
        movf d0, W
        subwf r0, F
        movf d1, W
        btfss STATUS, C
        incfsz d1, W
        subwf r1, F
        movf d2, W
        btfss STATUS, C
        incfsz d2, W
        subwf r2, F
        btfsc STATUS, C
        goto d_set
        movf d0, W
        addwf r0, F
        movf d1, W
        btfsc STATUS, C
        incfsz d1, W
        addwf r1, F
        movf d2, W
        btfsc STATUS, C
        incfsz d2, W
        addwf r2, F
        goto d_next
d_set:  bsf q0, 0
d_next: decfsz cnt, F
        goto d_loop
        return

; ---- sending ----
reply:  call send
line_end:
        movlw 0x0A
        goto tx

send_ram_line:
        call send_ram
        goto line_end

send:   movwf ptr               ; a message from the table, offset in W
s_loop: movf ptr, W
        call msg
        iorlw 0
        btfsc STATUS, Z
        return
        call tx
        incf ptr, F
        goto s_loop

send_ram:                       ; a 0-ended string in RAM at W
        movwf src
sr_loop:
        movf src, W
        movwf FSR
        movf INDF, W
        btfsc STATUS, Z
        return
        call tx
        incf src, F
        goto sr_loop

tx:     movwf txc               ; the 1 ms tick runs on while a reply goes out (12 ms for 12 bytes)
tx_w:   btfsc INTCON, T0IF
        call tick
        btfss PIR1, TXIF
        goto tx_w
        movf txc, W
        movwf TXREG
        return

        end
