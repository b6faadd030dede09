// SPDX-License-Identifier: GPL-2.0
/*
 * Simulated TS-7800 FPGA: a bit-level I2C slave on two DIO pins.
 *
 * Driven only by level changes of SCL and SDA (ts7800-sim-dio.c), exactly
 * like a chip on the wire:
 *  - SDA falling while SCL is high: START (or repeated START);
 *  - SDA rising while SCL is high: STOP;
 *  - SCL rising: the slave samples SDA (address, data, the master's ACK);
 *  - SCL falling: the slave changes what it drives on SDA (ACK, data bits).
 * The slave never stretches the clock. A byte addressed to another chip puts
 * it back to waiting for a START; a NACK from the master ends a read. Bytes
 * go to and come from the register model (ts7800-sim-max6615.c): the first
 * byte written after the address is the register pointer (SMBus byte-data).
 */
#include "ts7800-sim.h"

static void sim_i2c_load(struct ts7800_sim *sim)
{
	struct sim_i2c *bus = &sim->i2c;

	bus->shift = sim_max6615_read(&sim->fan);
	bus->bits = 0;
	bus->drive_low = !(bus->shift & 0x80);
	bus->state = SIM_I2C_RDATA;
}

static void sim_i2c_scl_rise(struct ts7800_sim *sim, bool sda)
{
	struct sim_i2c *bus = &sim->i2c;

	switch (bus->state) {
	case SIM_I2C_ADDR:
	case SIM_I2C_WDATA:
		if (bus->bits < 8) {
			bus->shift = bus->shift << 1 | sda;
			bus->bits++;
		}
		break;
	case SIM_I2C_RDATA_ACK:
		bus->acked = !sda;
		break;
	default:
		break;
	}
}

static void sim_i2c_scl_fall(struct ts7800_sim *sim)
{
	struct sim_i2c *bus = &sim->i2c;

	switch (bus->state) {
	case SIM_I2C_ADDR:
		if (bus->bits < 8)
			break;
		if (bus->shift >> 1 != sim->fan.addr) {
			bus->addr_nacks++;
			bus->state = SIM_I2C_IDLE;
			break;
		}
		bus->addr_acks++;
		bus->read = bus->shift & 1;
		bus->drive_low = true;
		bus->state = SIM_I2C_ADDR_ACK;
		break;
	case SIM_I2C_WDATA:
		if (bus->bits < 8)
			break;
		sim_max6615_write(&sim->fan, bus->shift, bus->first);
		bus->first = false;
		bus->drive_low = true;
		bus->state = SIM_I2C_WDATA_ACK;
		break;
	case SIM_I2C_ADDR_ACK:
		bus->drive_low = false;
		if (bus->read) {
			sim_i2c_load(sim);
			break;
		}
		bus->first = true;
		fallthrough;
	case SIM_I2C_WDATA_ACK:
		bus->drive_low = false;
		bus->bits = 0;
		bus->shift = 0;
		bus->state = SIM_I2C_WDATA;
		break;
	case SIM_I2C_RDATA:
		bus->bits++;
		bus->shift <<= 1;
		if (bus->bits == 8) {
			bus->drive_low = false;
			bus->acked = false;
			bus->state = SIM_I2C_RDATA_ACK;
		} else {
			bus->drive_low = !(bus->shift & 0x80);
		}
		break;
	case SIM_I2C_RDATA_ACK:
		if (bus->acked) {
			sim_i2c_load(sim);
		} else {
			bus->drive_low = false;
			bus->state = SIM_I2C_IDLE;
		}
		break;
	case SIM_I2C_IDLE:
		break;
	}
}

/**
 * sim_i2c_bus - the bus levels changed
 * @sim: the simulator (lock held)
 * @scl: new SCL level
 * @sda: new SDA level
 *
 * If both lines changed in one register write, the SDA change is taken
 * first (with SCL at its old level): the order a real chip would see is
 * undefined, this one is repeatable.
 */
void sim_i2c_bus(struct ts7800_sim *sim, bool scl, bool sda)
{
	struct sim_i2c *bus = &sim->i2c;

	if (sda != bus->sda && bus->scl) {
		if (!sda) {
			bus->starts++;
			bus->state = SIM_I2C_ADDR;
			bus->bits = 0;
			bus->shift = 0;
		} else {
			bus->stops++;
			bus->state = SIM_I2C_IDLE;
		}
		bus->drive_low = false;
	}
	bus->sda = sda;

	if (scl != bus->scl) {
		bus->scl = scl;
		if (scl)
			sim_i2c_scl_rise(sim, sda);
		else
			sim_i2c_scl_fall(sim);
	}
}
